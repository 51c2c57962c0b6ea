#include "io/h5.hpp"

#include <algorithm>

#include "common/error.hpp"

namespace erythro::io::h5 {
namespace {

std::string object_name(hid_t obj) {
  char buffer[512];
  const ssize_t n = H5Iget_name(obj, buffer, sizeof buffer);
  char file[512];
  const ssize_t m = H5Fget_name(obj, file, sizeof file);
  std::string where = m > 0 ? std::string(file) : std::string("?");
  return where + ":" + (n > 0 ? std::string(buffer) : std::string("?"));
}

[[noreturn]] void fail(const std::string& what) { throw OutputError("HDF5: " + what); }

hid_t check(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

void check_status(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

}  // namespace

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = other.id_;
    closer_ = other.closer_;
    other.id_ = -1;
  }
  return *this;
}

void Handle::reset() {
  if (id_ >= 0 && closer_) closer_(id_);
  id_ = -1;
}

void silence_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

Handle create_file(const std::string& path) {
  silence_errors();
  return {check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "cannot create file '" + path + "'"),
          H5Fclose};
}

Handle open_file_read(const std::string& path) {
  silence_errors();
  return {check(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "cannot open file '" + path + "'"), H5Fclose};
}

Handle create_group(hid_t parent, const std::string& name) {
  return {check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                "cannot create group '" + name + "' in " + object_name(parent)),
          H5Gclose};
}

Handle open_group(hid_t parent, const std::string& name) {
  return {check(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), "no group '" + name + "' in " + object_name(parent)),
          H5Gclose};
}

bool exists(hid_t parent, const std::string& name) { return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0; }
bool has_attr(hid_t obj, const std::string& name) { return H5Aexists(obj, name.c_str()) > 0; }

namespace {
// Replaces attribute `name` of obj with `value` (of HDF5 type `type`, shape `space`).
void write_attr_in(hid_t obj, const std::string& name, hid_t type, const Handle& space, const void* value) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  Handle attr(check(H5Acreate2(obj, name.c_str(), type, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                    "cannot create attribute '" + name + "' on " + object_name(obj)),
              H5Aclose);
  check_status(H5Awrite(attr.id(), type, value), "cannot write attribute '" + name + "'");
}

void write_scalar_attr(hid_t obj, const std::string& name, hid_t type, const void* value) {
  write_attr_in(obj, name, type, Handle(check(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose), value);
}

Handle open_attr(hid_t obj, const std::string& name) {
  return {check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "no attribute '" + name + "' on " + object_name(obj)),
          H5Aclose};
}

Handle string_type() {
  Handle type(check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
  check_status(H5Tset_size(type.id(), H5T_VARIABLE), "string type");
  check_status(H5Tset_cset(type.id(), H5T_CSET_UTF8), "string type");
  return type;
}
}  // namespace

void write_attr(hid_t obj, const std::string& name, double value) {
  write_scalar_attr(obj, name, H5T_NATIVE_DOUBLE, &value);
}

void write_attr(hid_t obj, const std::string& name, long value) {
  write_scalar_attr(obj, name, H5T_NATIVE_LONG, &value);
}

void write_attr(hid_t obj, const std::string& name, const std::string& value) {
  Handle type = string_type();
  const char* text = value.c_str();
  write_scalar_attr(obj, name, type.id(), &text);
}

void write_attr(hid_t obj, const std::string& name, const std::vector<double>& values) {
  const hsize_t n = values.size();
  write_attr_in(obj, name, H5T_NATIVE_DOUBLE, Handle(check(H5Screate_simple(1, &n, nullptr), "dataspace"), H5Sclose),
                values.data());
}

void write_attr(hid_t obj, const std::string& name, const std::vector<std::string>& values) {
  Handle type = string_type();
  std::vector<const char*> texts;
  for (const auto& v : values) texts.push_back(v.c_str());
  const hsize_t n = values.size();
  write_attr_in(obj, name, type.id(), Handle(check(H5Screate_simple(1, &n, nullptr), "dataspace"), H5Sclose),
                texts.data());
}

void write_attrs(hid_t obj, std::initializer_list<std::pair<const char*, AttrValue>> attrs) {
  for (const auto& [name, value] : attrs) std::visit([&](const auto& v) { write_attr(obj, name, v); }, value);
}

double read_attr_double(hid_t obj, const std::string& name) {
  Handle attr = open_attr(obj, name);
  double value = 0.0;
  check_status(H5Aread(attr.id(), H5T_NATIVE_DOUBLE, &value), "cannot read attribute '" + name + "'");
  return value;
}

std::string read_attr_string(hid_t obj, const std::string& name) {
  Handle attr = open_attr(obj, name);
  Handle type = string_type();
  char* text = nullptr;
  check_status(H5Aread(attr.id(), type.id(), &text), "cannot read attribute '" + name + "'");
  std::string value = text ? text : "";
  H5free_memory(text);
  return value;
}

void write_dataset(hid_t parent, const std::string& name, const std::vector<double>& data,
                   const std::vector<hsize_t>& dims) {
  Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "dataspace"), H5Sclose);
  Handle set(check(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   "cannot create dataset '" + name + "' in " + object_name(parent)),
             H5Dclose);
  if (!data.empty()) {
    check_status(H5Dwrite(set.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
                 "cannot write dataset '" + name + "'");
  }
}

void write_dataset(hid_t parent, const std::string& name, const std::vector<std::string>& data) {
  Handle type = string_type();
  const hsize_t n = data.size();
  Handle space(check(H5Screate_simple(1, &n, nullptr), "dataspace"), H5Sclose);
  Handle set(check(H5Dcreate2(parent, name.c_str(), type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   "cannot create dataset '" + name + "' in " + object_name(parent)),
             H5Dclose);
  std::vector<const char*> pointers;
  for (const auto& s : data) pointers.push_back(s.c_str());
  if (!data.empty()) {
    check_status(H5Dwrite(set.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()),
                 "cannot write dataset '" + name + "'");
  }
}

void write_dataset(hid_t parent, const std::string& name, const std::vector<long>& data,
                   const std::vector<hsize_t>& dims) {
  Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "dataspace"), H5Sclose);
  Handle set(check(H5Dcreate2(parent, name.c_str(), H5T_STD_I64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   "cannot create dataset '" + name + "' in " + object_name(parent)),
             H5Dclose);
  static_assert(sizeof(long) == 8, "integer datasets are written as 64-bit");
  if (!data.empty()) {
    check_status(H5Dwrite(set.id(), H5T_NATIVE_LONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
                 "cannot write dataset '" + name + "'");
  }
}

Handle open_dataset(hid_t parent, const std::string& name) {
  return Handle(check(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "no dataset '" + name + "' in " + object_name(parent)),
                H5Dclose);
}

std::vector<double> read_dataset(hid_t parent, const std::string& name, std::vector<hsize_t>* dims) {
  Handle set(check(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "no dataset '" + name + "' in " + object_name(parent)),
             H5Dclose);
  Handle space(check(H5Dget_space(set.id()), "dataspace"), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.id());
  std::vector<hsize_t> shape(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space.id(), shape.data(), nullptr);
  hsize_t count = 1;
  for (hsize_t d : shape) count *= d;
  std::vector<double> data(count);
  if (count > 0) {
    check_status(H5Dread(set.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
                 "cannot read dataset '" + name + "'");
  }
  if (dims) *dims = shape;
  return data;
}

AppendableSeries::AppendableSeries(hid_t parent, const std::string& name) {
  const hsize_t zero = 0, unlimited = H5S_UNLIMITED, chunk = 256;
  Handle space(check(H5Screate_simple(1, &zero, &unlimited), "dataspace"), H5Sclose);
  Handle props(check(H5Pcreate(H5P_DATASET_CREATE), "property list"), H5Pclose);
  check_status(H5Pset_chunk(props.id(), 1, &chunk), "chunking");
  dataset_ = Handle(check(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, props.id(), H5P_DEFAULT),
                          "cannot create series '" + name + "'"),
                    H5Dclose);
}

void AppendableSeries::append(double value) { append(std::span<const double>(&value, 1)); }

void AppendableSeries::append(std::span<const double> values) {
  if (values.empty()) return;
  const hsize_t count = values.size(), new_size = size_ + count, offset = size_;
  check_status(H5Dset_extent(dataset_.id(), &new_size), "cannot extend series");
  Handle file_space(check(H5Dget_space(dataset_.id()), "dataspace"), H5Sclose);
  check_status(H5Sselect_hyperslab(file_space.id(), H5S_SELECT_SET, &offset, nullptr, &count, nullptr), "hyperslab");
  Handle mem_space(check(H5Screate_simple(1, &count, nullptr), "dataspace"), H5Sclose);
  check_status(H5Dwrite(dataset_.id(), H5T_NATIVE_DOUBLE, mem_space.id(), file_space.id(), H5P_DEFAULT, values.data()),
               "cannot append to series");
  size_ += values.size();
}

std::vector<std::string> list(hid_t group) {
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->emplace_back(name);
    return 0;
  };
  H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names);
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> attribute_names(hid_t obj) {
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->emplace_back(name);
    return 0;
  };
  check_status(H5Aiterate2(obj, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names),
               "cannot list the attributes of " + object_name(obj));
  return names;
}

}  // namespace erythro::io::h5
