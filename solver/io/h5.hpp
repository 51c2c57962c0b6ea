#pragma once
// Thin RAII wrappers over the HDF5 C API: just what erythro writes and reads.
// Every call that can fail is checked, closes and flushes included (a full disk often
// shows only there): a failure throws OutputError naming the object and, where HDF5
// says, the system's reason ("No space left on device").
//
// Test hook: with ERYTHRO_FAULT_H5_WRITE_AFTER=N in the environment, the N-th write
// (dataset or attribute write, flush, file close) and every later one fail as if the
// disk were full (docs/cli.md), so the tests can end a run's output at any point.
#include <hdf5.h>

#include <initializer_list>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace erythro::io::h5 {

// Owns one hid_t and closes it with the matching H5*close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept { *this = std::move(other); }
  Handle& operator=(Handle&& other) noexcept;
  ~Handle() { reset(); }
  hid_t id() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes now; throws OutputError when HDF5 cannot (e.g. the last metadata does not fit on disk).
  void close();
  // Closes, ignoring a failure: for clean-up after an error has already been reported.
  void reset();

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

Handle create_file(const std::string& path);  // truncates
// Writes everything buffered for the file to disk (H5Fflush); throws OutputError.
void flush(hid_t file);
Handle open_file_read(const std::string& path);
Handle open_file_read_write(const std::string& path);
Handle create_group(hid_t parent, const std::string& name);
Handle open_group(hid_t parent, const std::string& name);
bool exists(hid_t parent, const std::string& name);         // a link (group, dataset)
bool has_attr(hid_t obj, const std::string& name);

void write_attr(hid_t obj, const std::string& name, double value);
void write_attr(hid_t obj, const std::string& name, long value);
void write_attr(hid_t obj, const std::string& name, const std::string& value);
void write_attr(hid_t obj, const std::string& name, const std::vector<double>& values);
void write_attr(hid_t obj, const std::string& name, const std::vector<std::string>& values);
// Several scalar attributes at once: write_attrs(g, {{"value", 1.0}, {"unit", "m"}}).
using AttrValue = std::variant<double, long, std::string>;
void write_attrs(hid_t obj, std::initializer_list<std::pair<const char*, AttrValue>> attrs);
double read_attr_double(hid_t obj, const std::string& name);
std::string read_attr_string(hid_t obj, const std::string& name);

// Contiguous datasets of float64 with the given shape (row-major, dims[0] slowest).
void write_dataset(hid_t parent, const std::string& name, const std::vector<double>& data,
                   const std::vector<hsize_t>& dims);
inline void write_dataset(hid_t parent, const std::string& name, const std::vector<double>& data) {
  write_dataset(parent, name, data, {static_cast<hsize_t>(data.size())});
}
void write_dataset(hid_t parent, const std::string& name, const std::vector<std::string>& data);
// Integer datasets (counts, indices) as 64-bit integers.
void write_dataset(hid_t parent, const std::string& name, const std::vector<long>& data,
                   const std::vector<hsize_t>& dims);
// The dataset `name` of `parent`, e.g. to give it attributes (write_attr on its id()).
Handle open_dataset(hid_t parent, const std::string& name);
std::vector<double> read_dataset(hid_t parent, const std::string& name, std::vector<hsize_t>* dims = nullptr);

// A growable float64 dataset (chunked), for time series written as a run goes: 1-D, or
// with `row_width` > 0 2-D (samples, row_width), one row per sample (a profile).
class AppendableSeries {
 public:
  AppendableSeries(hid_t parent, const std::string& name, std::size_t row_width = 0);
  void append(double value);
  // One extension and one write for a block (2-D: whole rows, values.size() a multiple of row_width).
  void append(std::span<const double> values);
  std::size_t size() const { return size_; }  // samples (rows)
  hid_t id() const { return dataset_.id(); }  // the dataset (for its attributes)
  void close() { dataset_.close(); }          // writes its last chunks; throws OutputError

 private:
  Handle dataset_;
  std::size_t size_ = 0;
  std::size_t row_width_ = 0;
};

// Names of the objects directly inside a group, sorted.
std::vector<std::string> list(hid_t group);
// Names of the attributes of an object, in creation order.
std::vector<std::string> attribute_names(hid_t obj);

// Call first in main(), before any other HDF5 call: turns off HDF5's automatic error
// printing (errors become exceptions instead) and its exit handler, which would try again
// to close a file whose close failed (disk full) and crash the process at exit. Every file
// is closed explicitly instead.
void prepare_library();

}  // namespace erythro::io::h5
