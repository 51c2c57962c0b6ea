#pragma once
// The state of a running simulation as named arrays of numbers (and a few texts): what a
// checkpoint holds (io/checkpoint.hpp). Each module puts what determines its future under
// its own prefix ("fluid.", "cells.", "transport.0.", ...) and takes it back on restart.
// Integers are kept as doubles, exact below 2^53 (step counts, node indices, flags), so one
// kind of array serves every module and the file needs one dataset type.
#include <algorithm>
#include <iterator>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "common/error.hpp"

namespace erythro {

class StateRecord {
 public:
  template <class Range>
  void put(const std::string& name, const Range& values) {
    arrays_[name] = std::vector<double>(std::begin(values), std::end(values));
  }
  void put_scalar(const std::string& name, double value) { arrays_[name] = {value}; }
  void put_text(const std::string& name, std::string text) { texts_[name] = std::move(text); }

  bool has(const std::string& name) const { return arrays_.count(name) > 0; }
  // The array `name`; throws InputError naming it when the checkpoint lacks it.
  const std::vector<double>& get(const std::string& name) const {
    const auto it = arrays_.find(name);
    if (it == arrays_.end()) throw InputError("checkpoint: no state entry '" + name + "'");
    return it->second;
  }
  // The same, of exactly `size` entries (the size of what it restores).
  const std::vector<double>& get(const std::string& name, std::size_t size) const {
    const std::vector<double>& v = get(name);
    if (v.size() != size)
      throw InputError("checkpoint: state entry '" + name + "' has " + std::to_string(v.size()) + " values, expected " +
                       std::to_string(size));
    return v;
  }
  double scalar(const std::string& name) const { return get(name, 1)[0]; }
  // The array converted to T (an integer type: the values were integers when put).
  template <class T>
  std::vector<T> get_as(const std::string& name) const {
    const std::vector<double>& v = get(name);
    return std::vector<T>(v.begin(), v.end());
  }
  // Copies the array into `out` (sizes must match).
  void copy_to(const std::string& name, std::span<double> out) const {
    const std::vector<double>& v = get(name, out.size());
    std::copy(v.begin(), v.end(), out.begin());
  }
  const std::string& text(const std::string& name) const {
    const auto it = texts_.find(name);
    if (it == texts_.end()) throw InputError("checkpoint: no state text '" + name + "'");
    return it->second;
  }

  const std::map<std::string, std::vector<double>>& arrays() const { return arrays_; }
  const std::map<std::string, std::string>& texts() const { return texts_; }

 private:
  std::map<std::string, std::vector<double>> arrays_;
  std::map<std::string, std::string> texts_;
};

}  // namespace erythro
