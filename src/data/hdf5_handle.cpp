#include "data/hdf5_handle.h"

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

void silence_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

namespace {
Handle checked(hid_t id, herr_t (*close)(hid_t), const std::string& what) {
  if (id < 0) throw DataError(what);
  return Handle(id, close);
}
void check(herr_t status, const std::string& what) {
  if (status < 0) throw DataError(what);
}
}  // namespace

namespace {
constexpr hsize_t kCompactBytes = 8 * 1024;  // well under the 64 KiB an object header can hold
}  // namespace

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
  // Small datasets live in the object header: a chunked one costs kilobytes of index and
  // header whatever its size, which tripled the arm's file (50-step episodes).
  const bool small = elements * H5Tget_size(file_type) <= kCompactBytes;
  if (elements > 0 && small) {
    check(H5Pset_layout(plist.get(), H5D_COMPACT), where + ": compact layout");
  } else if (elements > 0) {
    check(H5Pset_chunk(plist.get(), static_cast<int>(dims.size()), dims.data()), where + ": chunking");
    check(H5Pset_shuffle(plist.get()), where + ": shuffle filter");
    check(H5Pset_deflate(plist.get(), 4), where + ": deflate filter");
  }
  Handle ds = checked(H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                 plist.get(), H5P_DEFAULT),
                      H5Dclose, where + ": cannot create dataset " + name);
  if (elements > 0)
    check(H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
          where + ": cannot write dataset " + name);
}

void write_string_attr(hid_t obj, const std::string& name, const std::string& value) {
  Handle type = checked(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr = checked(H5Acreate2(obj, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                        H5Aclose, "cannot create attribute " + name);
  const char* text = value.c_str();
  check(H5Awrite(attr.get(), type.get(), &text), "cannot write attribute " + name);
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

bool has_link(hid_t parent, const std::string& name) {
  return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0;
}

std::vector<hsize_t> dataset_shape(hid_t dataset) {
  Handle space(H5Dget_space(dataset), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(rank > 0 ? rank : 0);
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

bool has_attr(hid_t obj, const std::string& name) { return H5Aexists(obj, name.c_str()) > 0; }

std::string read_string_attr(hid_t obj, const std::string& name, const std::string& where) {
  if (!has_attr(obj, name)) throw DataError(where + ": missing attribute '" + name + "'");
  Handle attr = checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, where + ": attribute " + name);
  Handle type = checked(H5Aget_type(attr.get()), H5Tclose, where + ": attribute " + name);
  if (H5Tget_class(type.get()) != H5T_STRING)
    throw DataError(where + ": attribute '" + name + "' is not a string");
  if (H5Tis_variable_str(type.get()) > 0) {
    char* text = nullptr;
    check(H5Aread(attr.get(), type.get(), &text), where + ": cannot read attribute " + name);
    std::string value = text ? text : "";
    H5free_memory(text);
    return value;
  }
  std::string value(H5Tget_size(type.get()), '\0');
  check(H5Aread(attr.get(), type.get(), value.data()), where + ": cannot read attribute " + name);
  return value.substr(0, value.find('\0'));
}

std::vector<double> read_double_attr(hid_t obj, const std::string& name, const std::string& where) {
  if (!has_attr(obj, name)) throw DataError(where + ": missing attribute '" + name + "'");
  Handle attr = checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, where + ": attribute " + name);
  Handle type = checked(H5Aget_type(attr.get()), H5Tclose, where + ": attribute " + name);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    throw DataError(where + ": attribute '" + name + "' is not numeric");
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  std::vector<double> values(n > 0 ? n : 0);
  if (n > 0) check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, values.data()), where + ": cannot read attribute " + name);
  return values;
}

std::vector<std::string> attr_names(hid_t obj) {
  std::vector<std::string> names;
  H5O_info_t info;
  if (H5Oget_info2(obj, &info, H5O_INFO_NUM_ATTRS) < 0) return names;
  for (hsize_t i = 0; i < info.num_attrs; ++i) {
    char buf[256];
    if (H5Aget_name_by_idx(obj, ".", H5_INDEX_NAME, H5_ITER_INC, i, buf, sizeof buf, H5P_DEFAULT) >= 0)
      names.emplace_back(buf);
  }
  return names;
}

}  // namespace vaegail::h5
