#include "data/hdf5_handle.h"

#include <algorithm>

#include "data/demos.h"

namespace vaegail::h5 {

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = -1;
  }
  return *this;
}

void Handle::reset() {
  if (id_ >= 0 && close_) close_(id_);
  id_ = -1;
}

hid_t Handle::release() {
  const hid_t id = id_;
  id_ = -1;
  return id;
}

void silence_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

namespace {
// HDF5 describes a failed system call over more than a line: ctime's newline, the buffer's
// address, sizes and offsets ("file write failed: time = ...\n, filename = ..., errno = 28, error
// message = 'No space left on device', buf = ..."). Its own words and the system's message say it.
std::string readable_cause(const std::string& description) {
  const std::string tag = "error message = '";
  const auto at = description.find(tag);
  if (at == std::string::npos) {
    std::string line = description;
    std::replace(line.begin(), line.end(), '\n', ' ');
    return line;
  }
  const auto start = at + tag.size();
  return description.substr(0, description.find(':')) + ": " +
         description.substr(start, description.find('\'', start) - start);
}
}  // namespace

std::string with_cause(const std::string& what) {
  std::string cause;
  // Walking upward starts at the frame where HDF5 first noticed the problem.
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD,
           [](unsigned n, const H5E_error2_t* err, void* out) -> herr_t {
             if (n == 0 && err->desc) *static_cast<std::string*>(out) = err->desc;
             return 0;
           },
           &cause);
  return cause.empty() ? what : what + " (" + readable_cause(cause) + ")";
}

namespace {
Handle checked(hid_t id, herr_t (*close)(hid_t), const std::string& what) {
  if (id < 0) throw DataError(with_cause(what));
  return Handle(id, close);
}
void check(herr_t status, const std::string& what) {
  if (status < 0) throw DataError(with_cause(what));
}
// Beyond any name list or per-episode value the format stores; a larger size is corruption.
constexpr hsize_t kMaxAttributeBytes = hsize_t(1) << 24;

// Bob Jenkins' lookup3 hash (hashlittle, public domain), which HDF5 checksums its metadata with.
std::uint32_t lookup3(const unsigned char* key, size_t length) {
  const auto rot = [](std::uint32_t x, int k) { return (x << k) | (x >> (32 - k)); };
  const auto word = [](const unsigned char* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
  };
  std::uint32_t a, b, c;
  a = b = c = 0xdeadbeef + static_cast<std::uint32_t>(length);
  for (; length > 12; length -= 12, key += 12) {
    a += word(key), b += word(key + 4), c += word(key + 8);
    a -= c, a ^= rot(c, 4), c += b, b -= a, b ^= rot(a, 6), a += c, c -= b, c ^= rot(b, 8), b += a;
    a -= c, a ^= rot(c, 16), c += b, b -= a, b ^= rot(a, 19), a += c, c -= b, c ^= rot(b, 4), b += a;
  }
  if (length == 0) return c;
  unsigned char tail[12] = {};
  std::copy(key, key + length, tail);
  a += word(tail), b += word(tail + 4), c += word(tail + 8);
  c ^= b, c -= rot(b, 14), a ^= c, a -= rot(c, 11), b ^= a, b -= rot(a, 25), c ^= b, c -= rot(b, 16);
  a ^= c, a -= rot(c, 4), b ^= a, b -= rot(a, 14), c ^= b, c -= rot(b, 24);
  return c;
}

// H5Fget_file_image (HDF5 1.10.8) clears the superblock's status flags, as for a closed file,
// without computing the superblock's checksum again, so that the image fails to open
// ("incorrect metadata checksum"). A superblock of version 2 or 3 (the 1.10 format) is 12 bytes
// and 4 addresses, then the checksum of those.
void checksum_superblock(std::string& image) {
  if (image.size() < 12 || (image[8] != 2 && image[8] != 3)) return;
  const size_t end = 12 + 4 * static_cast<size_t>(static_cast<unsigned char>(image[9]));
  if (image.size() < end + 4) return;
  const std::uint32_t sum = lookup3(reinterpret_cast<const unsigned char*>(image.data()), end);
  for (size_t i = 0; i < 4; ++i) image[end + i] = static_cast<char>(sum >> (8 * i));
}
}  // namespace

Handle create_file_in_memory(const std::string& name, const std::string& where) {
  Handle access = checked(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, where + ": property list");
  check(H5Pset_fapl_core(access.get(), 1 << 20, /*backing_store=*/false), where + ": in-memory file");
  // The 1.10 format checksums all metadata; files need HDF5 1.10 or later (h5py >= 2.7) to read.
  check(H5Pset_libver_bounds(access.get(), H5F_LIBVER_V110, H5F_LIBVER_V110), where + ": file format");
  // The root group is created with the file: untimed like every other object.
  Handle creation = checked(H5Pcreate(H5P_FILE_CREATE), H5Pclose, where + ": property list");
  check(H5Pset_obj_track_times(creation.get(), false), where + ": untimed root group");
  return checked(H5Fcreate(name.c_str(), H5F_ACC_TRUNC, creation.get(), access.get()), H5Fclose,
                 where + ": cannot create file");
}

std::string file_image(hid_t file, const std::string& where) {
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), where + ": cannot flush file");
  const ssize_t size = H5Fget_file_image(file, nullptr, 0);
  if (size < 0) throw DataError(with_cause(where + ": cannot take the file's image"));
  std::string image(static_cast<size_t>(size), '\0');
  if (H5Fget_file_image(file, image.data(), image.size()) != size)
    throw DataError(with_cause(where + ": cannot take the file's image"));
  checksum_superblock(image);
  return image;
}

Handle create_group(hid_t parent, const std::string& name, const std::string& where) {
  Handle plist = checked(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, where + ": property list");
  check(H5Pset_obj_track_times(plist.get(), false), where + ": untimed group");
  return checked(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, plist.get(), H5P_DEFAULT), H5Gclose,
                 where + ": cannot create group " + name);
}

void write_dataset(hid_t parent, const std::string& name, hid_t mem_type, hid_t file_type,
                   const std::vector<hsize_t>& dims, const void* data, const std::string& where) {
  Handle space = checked(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                         H5Sclose, where + ": cannot describe dataset " + name);
  Handle plist = checked(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, where + ": property list");
  check(H5Pset_obj_track_times(plist.get(), false), where + ": untimed dataset");
  hsize_t elements = 1;
  for (hsize_t d : dims) elements *= d;
  // One chunk per dataset, so that every value sits under a checksum; the 1.10 format indexes
  // a single chunk from the object header, so small datasets cost no B-tree. Fletcher-32 comes
  // last: reading checks the stored bytes before inflating them.
  if (elements > 0) {
    check(H5Pset_chunk(plist.get(), static_cast<int>(dims.size()), dims.data()), where + ": chunking");
    check(H5Pset_shuffle(plist.get()), where + ": shuffle filter");
    check(H5Pset_deflate(plist.get(), 4), where + ": deflate filter");
    check(H5Pset_fletcher32(plist.get()), where + ": checksum filter");
  }
  Handle ds = checked(H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                 plist.get(), H5P_DEFAULT),
                      H5Dclose, where + ": cannot create dataset " + name);
  if (elements > 0)
    check(H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
          where + ": cannot write dataset " + name);
}

void write_string_attr(hid_t obj, const std::string& name, const std::string& value) {
  // Fixed length, padded like numpy's bytes: stored in the (checksummed) object header.
  Handle type = checked(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(type.get(), std::max<size_t>(1, value.size())), "string size");
  check(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), "string padding");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "string encoding");
  Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr = checked(H5Acreate2(obj, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                        H5Aclose, "cannot create attribute " + name);
  std::string padded = value;
  padded.resize(H5Tget_size(type.get()), '\0');
  check(H5Awrite(attr.get(), type.get(), padded.data()), "cannot write attribute " + name);
}

void write_double_attr(hid_t obj, const std::string& name, const std::vector<double>& values) {
  const hsize_t n = values.size();
  Handle space = checked(n ? H5Screate_simple(1, &n, nullptr) : H5Screate(H5S_NULL), H5Sclose, "space");
  Handle attr = checked(H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                        H5Aclose, "cannot create attribute " + name);
  if (n) check(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, values.data()), "cannot write attribute " + name);
}

void write_scalar_attr(hid_t obj, const std::string& name, hid_t mem_type, hid_t file_type, const void* value) {
  Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr = checked(H5Acreate2(obj, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                        H5Aclose, "cannot create attribute " + name);
  check(H5Awrite(attr.get(), mem_type, value), "cannot write attribute " + name);
}

Handle bool_type() {
  Handle type = checked(H5Tenum_create(H5T_NATIVE_INT8), H5Tclose, "bool type");
  const signed char no = 0, yes = 1;
  H5Tenum_insert(type.get(), "FALSE", &no);
  H5Tenum_insert(type.get(), "TRUE", &yes);
  return type;
}

void require_link(hid_t parent, const std::string& name, const std::string& where, const std::string& kind) {
  const htri_t exists = H5Lexists(parent, name.c_str(), H5P_DEFAULT);
  if (exists < 0) throw DataError(with_cause(where + ": cannot look up " + kind));
  if (exists == 0) throw DataError(where + ": missing " + kind);
}

std::string shape_text(const std::vector<hsize_t>& dims) {
  std::string s = "[";
  for (size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + "]";
}

bool has_link(hid_t parent, const std::string& name, const std::string& where) {
  const htri_t exists = H5Lexists(parent, name.c_str(), H5P_DEFAULT);
  if (exists < 0) throw DataError(with_cause(where + ": cannot look up " + name));
  return exists > 0;
}

template <typename T>
void read_dataset(hid_t group, const std::string& name, H5T_class_t cls, hid_t mem_type,
                  const std::vector<hsize_t>& expected, std::vector<T>& out, const std::string& where) {
  const std::string field = where + "/" + name;
  require_link(group, name, field, "dataset");
  Handle ds(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) throw DataError(with_cause(field + ": cannot open dataset"));
  Handle type(H5Dget_type(ds.get()), H5Tclose);
  const H5T_class_t found = H5Tget_class(type.get());
  const bool is_bool = cls == H5T_ENUM;
  const bool type_ok = is_bool ? ((found == H5T_ENUM || found == H5T_INTEGER) && H5Tget_size(type.get()) == 1)
                               : found == cls;
  if (!type_ok)
    throw DataError(field + ": wrong dtype (expected " +
                    (is_bool ? std::string("bool") : cls == H5T_FLOAT ? "float" : "integer") + ")");
  const auto dims = dataset_shape(ds.get());
  if (dims != expected)
    throw DataError(field + ": shape " + shape_text(dims) + ", expected " + shape_text(expected));
  out.resize(checked_elements(dims, sizeof(T), field));
  // 1-byte booleans are read as stored: HDF5 does not convert enums to integers.
  const hid_t read_type = is_bool ? type.get() : mem_type;
  if (!out.empty() && H5Dread(ds.get(), read_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw DataError(with_cause(field + ": cannot read"));
}

template void read_dataset<float>(hid_t, const std::string&, H5T_class_t, hid_t, const std::vector<hsize_t>&,
                                  std::vector<float>&, const std::string&);
template void read_dataset<double>(hid_t, const std::string&, H5T_class_t, hid_t, const std::vector<hsize_t>&,
                                   std::vector<double>&, const std::string&);
template void read_dataset<std::uint8_t>(hid_t, const std::string&, H5T_class_t, hid_t,
                                         const std::vector<hsize_t>&, std::vector<std::uint8_t>&,
                                         const std::string&);

std::vector<hsize_t> dataset_dims(hid_t group, const std::string& name, const std::string& where) {
  require_link(group, name, where + "/" + name, "dataset");
  Handle ds(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) throw DataError(with_cause(where + "/" + name + ": cannot open dataset"));
  return dataset_shape(ds.get());
}

std::vector<hsize_t> dataset_shape(hid_t dataset) {
  Handle space(H5Dget_space(dataset), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(rank > 0 ? rank : 0);
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

hsize_t checked_elements(const std::vector<hsize_t>& dims, size_t element_bytes, const std::string& where) {
  const hsize_t limit = kMaxDatasetBytes / std::max<size_t>(1, element_bytes);
  hsize_t n = 1;
  for (hsize_t d : dims) {
    if (d > 0 && n > limit / d)
      throw DataError(where + ": dataset of more than " + std::to_string(kMaxDatasetBytes) +
                      " bytes (corrupt dimensions?)");
    n *= d;
  }
  return n;
}

hsize_t link_count(hid_t group) {
  H5G_info_t info;
  return H5Gget_info(group, &info) < 0 ? 0 : info.nlinks;
}

namespace {
void require_attr(hid_t obj, const std::string& name, const std::string& where) {
  const htri_t exists = H5Aexists(obj, name.c_str());
  if (exists < 0) throw DataError(with_cause(where + ": cannot look up attribute '" + name + "'"));
  if (exists == 0) throw DataError(where + ": missing attribute '" + name + "'");
}
}  // namespace

std::string read_string_attr(hid_t obj, const std::string& name, const std::string& where) {
  require_attr(obj, name, where);
  Handle attr = checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, where + ": attribute " + name);
  Handle type = checked(H5Aget_type(attr.get()), H5Tclose, where + ": attribute " + name);
  if (H5Tget_class(type.get()) != H5T_STRING)
    throw DataError(where + ": attribute '" + name + "' is not a string");
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1)
    throw DataError(where + ": attribute '" + name + "' is not a single string");
  // Files of other tools (h5py) store variable-length strings; this program writes fixed ones.
  if (H5Tis_variable_str(type.get()) > 0) {
    char* text = nullptr;
    check(H5Aread(attr.get(), type.get(), &text), where + ": cannot read attribute " + name);
    std::string value = text ? text : "";
    H5free_memory(text);
    return value;
  }
  const size_t size = H5Tget_size(type.get());
  if (size == 0 || size > kMaxAttributeBytes)
    throw DataError(where + ": attribute '" + name + "' of " + std::to_string(size) + " bytes (corrupt?)");
  std::string value(size, '\0');
  check(H5Aread(attr.get(), type.get(), value.data()), where + ": cannot read attribute " + name);
  return value.substr(0, value.find('\0'));
}

std::vector<double> read_double_attr(hid_t obj, const std::string& name, const std::string& where) {
  require_attr(obj, name, where);
  Handle attr = checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, where + ": attribute " + name);
  Handle type = checked(H5Aget_type(attr.get()), H5Tclose, where + ": attribute " + name);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    throw DataError(where + ": attribute '" + name + "' is not numeric");
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0 || hsize_t(n) > kMaxAttributeBytes / sizeof(double))
    throw DataError(where + ": attribute '" + name + "' of " + std::to_string(n) + " values (corrupt?)");
  std::vector<double> values(n);
  if (n > 0) check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, values.data()), where + ": cannot read attribute " + name);
  return values;
}

std::vector<std::string> attr_names(hid_t obj) {
  std::vector<std::string> names;
  // Iterating visits the attributes there are, whatever count a corrupted header claims.
  hsize_t position = 0;
  H5Aiterate2(obj, H5_INDEX_NAME, H5_ITER_INC, &position,
              [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
                static_cast<std::vector<std::string>*>(out)->emplace_back(name);
                return 0;
              },
              &names);
  return names;
}

}  // namespace vaegail::h5
