#pragma once
// Regression check: compares every float dataset of a baseline HDF5 file with the
// same dataset in a current file, with per-quantity absolute + relative tolerances:
//   |current − baseline| ≤ atol + rtol·|baseline|   element-wise.
// Tolerances come from a TOML file (reference_data/baselines/tolerances.toml):
//   [default]             atol = ..., rtol = ...
//   [quantity.<name>]     atol = ..., rtol = ...   (<name>: last path component, e.g. velocity)
#include <string>
#include <vector>

namespace erythro::io {

struct Tolerance {
  double atol = 0.0;
  double rtol = 0.0;
};

struct DatasetComparison {
  std::string path;  // e.g. /fields/0000000500/velocity
  Tolerance tolerance;
  bool present = true;         // dataset exists in the current file with the same shape
  double max_abs_diff = 0.0;   // over elements
  double max_rel_diff = 0.0;   // |diff|/|baseline| over elements with baseline ≠ 0
  std::size_t worst_index = 0; // element with the largest excess over its tolerance
  double worst_baseline = 0.0, worst_current = 0.0;
  bool passed = true;
};

struct BaselineReport {
  std::vector<DatasetComparison> datasets;
  bool passed() const;
  std::string to_text() const;  // one line per dataset: what moved and by how much
};

BaselineReport compare_to_baseline(const std::string& current_h5, const std::string& baseline_h5,
                                   const std::string& tolerances_toml);

}  // namespace erythro::io
