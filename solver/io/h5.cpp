#include "io/h5.hpp"

#include <algorithm>
#include <cstdlib>
#include <utility>

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

// The most specific entry of HDF5's error stack, which for a failed write holds the
// system's reason: "... errno = 28, error message = 'No space left on device', ...".
// Returns that reason, or the entry's whole description, or "" when the stack is empty.
std::string innermost_error() {
  std::string description;
  auto first = [](unsigned depth, const H5E_error2_t* error, void* out) -> herr_t {
    if (depth == 0 && error->desc) *static_cast<std::string*>(out) = error->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, first, &description);
  const std::string key = "error message = '";
  const std::size_t begin = description.find(key);
  if (begin == std::string::npos) return description;
  const std::size_t end = description.find('\'', begin + key.size());
  return description.substr(begin + key.size(), end - begin - key.size());
}

[[noreturn]] void fail(const std::string& what) {
  const std::string reason = innermost_error();
  throw OutputError("HDF5: " + what + (reason.empty() ? "" : ": " + reason));
}

hid_t check(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

void check_status(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

// The test hook ERYTHRO_FAULT_H5_WRITE_AFTER=N (h5.hpp): true for the N-th write of the
// process and every later one, as on a disk that has filled up.
bool write_fault_injected() {
  static const long first_failing = [] {
    const char* value = std::getenv("ERYTHRO_FAULT_H5_WRITE_AFTER");
    return value ? std::atol(value) : 0L;
  }();
  static long writes = 0;
  return first_failing > 0 && ++writes >= first_failing;
}

[[noreturn]] void fail_injected(const std::string& what) {
  throw OutputError("HDF5: " + what + ": No space left on device (injected by ERYTHRO_FAULT_H5_WRITE_AFTER)");
}

// Runs `write` (an HDF5 call that writes, returning its status) unless the test hook
// fails it first.
template <class Write>
void checked_write(Write&& write, const std::string& what) {
  if (write_fault_injected()) fail_injected(what);
  check_status(write(), what);
}

void silence_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

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

void Handle::close() {
  if (id_ < 0 || !closer_) return;
  const std::string what = "cannot close " + object_name(id_);
  const bool is_file = closer_ == &H5Fclose;
  const hid_t id = std::exchange(id_, -1);
  // The handle is released even when the close fails: HDF5 has given up on it.
  const bool closed = closer_(id) >= 0;
  if (is_file && write_fault_injected()) fail_injected(what);
  if (!closed) fail(what);
}

void Handle::reset() {
  if (id_ >= 0 && closer_) closer_(id_);
  id_ = -1;
}

void prepare_library() {
  H5dont_atexit();
  silence_errors();
}

Handle create_file(const std::string& path) {
  silence_errors();
  return {check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "cannot create file '" + path + "'"),
          H5Fclose};
}

void flush(hid_t file) {
  checked_write([&] { return H5Fflush(file, H5F_SCOPE_GLOBAL); }, "cannot flush " + object_name(file));
}

Handle open_file_read(const std::string& path) {
  silence_errors();
  return {check(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "cannot open file '" + path + "'"), H5Fclose};
}

Handle open_file_read_write(const std::string& path) {
  silence_errors();
  return {check(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "cannot open file '" + path + "' for writing"),
          H5Fclose};
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

bool exists(hid_t parent, const std::string& name) {
  const htri_t found = H5Lexists(parent, name.c_str(), H5P_DEFAULT);
  check_status(found, "cannot look for '" + name + "'");
  return found > 0;
}

bool has_attr(hid_t obj, const std::string& name) {
  const htri_t found = H5Aexists(obj, name.c_str());
  check_status(found, "cannot look for attribute '" + name + "'");
  return found > 0;
}

namespace {
// Replaces attribute `name` of obj with `value` (of HDF5 type `type`, shape `space`).
void write_attr_in(hid_t obj, const std::string& name, hid_t type, const Handle& space, const void* value) {
  if (has_attr(obj, name)) check_status(H5Adelete(obj, name.c_str()), "cannot replace attribute '" + name + "'");
  Handle attr(check(H5Acreate2(obj, name.c_str(), type, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                    "cannot create attribute '" + name + "' on " + object_name(obj)),
              H5Aclose);
  checked_write([&] { return H5Awrite(attr.id(), type, value); }, "cannot write attribute '" + name + "'");
  attr.close();
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
    checked_write([&] { return H5Dwrite(set.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()); },
                  "cannot write dataset '" + name + "'");
  }
  set.close();
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
    checked_write([&] { return H5Dwrite(set.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()); },
                  "cannot write dataset '" + name + "'");
  }
  set.close();
}

void write_dataset(hid_t parent, const std::string& name, const std::vector<long>& data,
                   const std::vector<hsize_t>& dims) {
  Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "dataspace"), H5Sclose);
  Handle set(check(H5Dcreate2(parent, name.c_str(), H5T_STD_I64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   "cannot create dataset '" + name + "' in " + object_name(parent)),
             H5Dclose);
  static_assert(sizeof(long) == 8, "integer datasets are written as 64-bit");
  if (!data.empty()) {
    checked_write([&] { return H5Dwrite(set.id(), H5T_NATIVE_LONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()); },
                  "cannot write dataset '" + name + "'");
  }
  set.close();
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
  check_status(rank, "cannot read the shape of dataset '" + name + "'");
  std::vector<hsize_t> shape(static_cast<std::size_t>(rank));
  check_status(H5Sget_simple_extent_dims(space.id(), shape.data(), nullptr),
               "cannot read the shape of dataset '" + name + "'");
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

AppendableSeries::AppendableSeries(hid_t parent, const std::string& name, std::size_t row_width)
    : row_width_(row_width) {
  const int rank = row_width > 0 ? 2 : 1;
  const hsize_t zero[2] = {0, row_width}, unlimited[2] = {H5S_UNLIMITED, row_width};
  // 256 samples of a series; about 2048 values of a profile (at least one row)
  const hsize_t chunk[2] = {row_width > 0 ? std::max<hsize_t>(1, 2048 / row_width) : 256, row_width};
  Handle space(check(H5Screate_simple(rank, zero, unlimited), "dataspace"), H5Sclose);
  Handle props(check(H5Pcreate(H5P_DATASET_CREATE), "property list"), H5Pclose);
  check_status(H5Pset_chunk(props.id(), rank, chunk), "chunking");
  dataset_ = Handle(check(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, props.id(), H5P_DEFAULT),
                          "cannot create series '" + name + "'"),
                    H5Dclose);
}

void AppendableSeries::append(double value) { append(std::span<const double>(&value, 1)); }

void AppendableSeries::append(std::span<const double> values) {
  if (values.empty()) return;
  const int rank = row_width_ > 0 ? 2 : 1;
  const hsize_t rows = row_width_ > 0 ? values.size() / row_width_ : values.size();
  if (row_width_ > 0 && rows * row_width_ != values.size())
    throw OutputError("HDF5: " + std::to_string(values.size()) + " values are not whole rows of " +
                      std::to_string(row_width_) + " for " + object_name(dataset_.id()));
  const hsize_t count[2] = {rows, row_width_}, new_size[2] = {size_ + rows, row_width_}, offset[2] = {size_, 0};
  check_status(H5Dset_extent(dataset_.id(), new_size), "cannot extend series");
  Handle file_space(check(H5Dget_space(dataset_.id()), "dataspace"), H5Sclose);
  check_status(H5Sselect_hyperslab(file_space.id(), H5S_SELECT_SET, offset, nullptr, count, nullptr), "hyperslab");
  Handle mem_space(check(H5Screate_simple(rank, count, nullptr), "dataspace"), H5Sclose);
  const auto write = [&] {
    return H5Dwrite(dataset_.id(), H5T_NATIVE_DOUBLE, mem_space.id(), file_space.id(), H5P_DEFAULT, values.data());
  };
  checked_write(write, "cannot append to series " + object_name(dataset_.id()));
  size_ += rows;
}

std::vector<std::string> list(hid_t group) {
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->emplace_back(name);
    return 0;
  };
  check_status(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names),
               "cannot list " + object_name(group));
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
