// Thin RAII and typed helpers over the HDF5 C API, shared by the demonstration reader and
// writer. Errors throw DataError with a caller-supplied location; HDF5's own error stack
// printing is switched off so users see one line, not a trace.
#pragma once

#include <hdf5.h>

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

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

void silence_errors();

// Writing. `where` names the object in error messages. Objects carry no creation or
// modification times, so that the same episodes make the same bytes.
Handle create_group(hid_t parent, const std::string& name, const std::string& where);
void write_dataset(hid_t parent, const std::string& name, hid_t mem_type, hid_t file_type,
                   const std::vector<hsize_t>& dims, const void* data, const std::string& where);
void write_string_attr(hid_t obj, const std::string& name, const std::string& value);
void write_double_attr(hid_t obj, const std::string& name, const std::vector<double>& values);
void write_scalar_attr(hid_t obj, const std::string& name, hid_t mem_type, hid_t file_type, const void* value);
// h5py's representation of numpy bool: an enum of int8 with members FALSE and TRUE.
Handle bool_type();

// Reading.
bool has_link(hid_t parent, const std::string& name);
std::vector<hsize_t> dataset_shape(hid_t dataset);
std::string read_string_attr(hid_t obj, const std::string& name, const std::string& where);
std::vector<double> read_double_attr(hid_t obj, const std::string& name, const std::string& where);
bool has_attr(hid_t obj, const std::string& name);
std::vector<std::string> attr_names(hid_t obj);

}  // namespace vaegail::h5
