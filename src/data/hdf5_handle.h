// Thin RAII and typed helpers over the HDF5 C API, shared by the demonstration reader and
// writer. Errors throw DataError with a caller-supplied location; HDF5's own error stack
// printing is switched off so users see one line, not a trace.
//
// What the writer stores can check itself: the file format of HDF5 1.10 (checksums on the
// superblock, object headers, heaps and chunk indices), every non-empty dataset chunked with
// the Fletcher-32 filter, and strings fixed-length (a variable-length string lives in the
// global heap, which carries no checksum: a flipped byte there crashed libhdf5).
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace vaegail::h5 {

class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset();
  hid_t release();  // the caller closes the id from now on

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

void silence_errors();
// `what` followed by the innermost message on HDF5's error stack, the reason for the call
// that just failed (e.g. "(data error detected by Fletcher32 checksum)"), when there is one.
std::string with_cause(const std::string& what);

// Writing. `where` names the object in error messages. Objects carry no creation or
// modification times, so that the same episodes make the same bytes.
// A file in memory (the core driver, no backing store), which file_image turns into bytes to
// write; `name` only tells open files apart.
Handle create_file_in_memory(const std::string& name, const std::string& where);
// The bytes of the file as a disk would hold them once it is closed.
std::string file_image(hid_t file, const std::string& where);
Handle create_group(hid_t parent, const std::string& name, const std::string& where);
void write_dataset(hid_t parent, const std::string& name, hid_t mem_type, hid_t file_type,
                   const std::vector<hsize_t>& dims, const void* data, const std::string& where);
void write_string_attr(hid_t obj, const std::string& name, const std::string& value);
void write_double_attr(hid_t obj, const std::string& name, const std::vector<double>& values);
void write_scalar_attr(hid_t obj, const std::string& name, hid_t mem_type, hid_t file_type, const void* value);
// h5py's representation of numpy bool: an enum of int8 with members FALSE and TRUE.
Handle bool_type();

// Reading. Every size a file states is checked before memory is allocated for it: a
// corrupted dimension must end in an error, not in a multi-terabyte allocation.
// Throws "`where`: missing `kind`" when `parent` has no link `name`, or HDF5's reason when the
// lookup itself fails (a corrupted link table must not read as a missing dataset).
void require_link(hid_t parent, const std::string& name, const std::string& where, const std::string& kind);
// Whether `parent` has a link `name`; throws HDF5's reason when the lookup fails.
bool has_link(hid_t parent, const std::string& name, const std::string& where);
std::vector<hsize_t> dataset_shape(hid_t dataset);
// The shape of dataset `name` under `group` (which must have it).
std::vector<hsize_t> dataset_dims(hid_t group, const std::string& name, const std::string& where);
// "[3, 4]"
std::string shape_text(const std::vector<hsize_t>& dims);
// Opens dataset `name`, checks its type class (H5T_FLOAT, H5T_INTEGER, or H5T_ENUM for 1-byte
// booleans) and its shape against `expected`, and reads it into `out` converted to `mem_type`.
// Messages name `where`/`name`. Defined for float, double and std::uint8_t.
template <typename T>
void read_dataset(hid_t group, const std::string& name, H5T_class_t cls, hid_t mem_type,
                  const std::vector<hsize_t>& expected, std::vector<T>& out, const std::string& where);
// The number of elements of `dims`; throws when they overflow or `element_bytes` each would
// exceed what a demonstration file holds (kMaxDatasetBytes).
hsize_t checked_elements(const std::vector<hsize_t>& dims, size_t element_bytes, const std::string& where);
constexpr hsize_t kMaxDatasetBytes = hsize_t(1) << 32;
// Links directly under a group (episode groups under the root).
hsize_t link_count(hid_t group);
std::string read_string_attr(hid_t obj, const std::string& name, const std::string& where);
std::vector<double> read_double_attr(hid_t obj, const std::string& name, const std::string& where);
std::vector<std::string> attr_names(hid_t obj);

}  // namespace vaegail::h5
