#pragma once
// What every `erythro bench` section shares: the summary of repeated samples, and the
// metric of a measured speed, recorded with the comparison `at_least −inf`, so the record
// holds it without ever asserting it (any finite value passes).
#include <algorithm>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "io/result_record.hpp"

namespace erythro::app {

// Median, smallest and largest of repeated samples.
struct Stats {
  double median = 0.0, min = 0.0, max = 0.0;
  double spread() const { return median > 0.0 ? (max - min) / median : 0.0; }
};

inline Stats stats_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {median, v.front(), v.back()};
}

inline io::Metric informative(std::string name, std::string description, std::string unit, double value) {
  io::Metric m;
  m.name = std::move(name);
  m.description = std::move(description);
  m.unit = std::move(unit);
  m.value = value;
  // Any finite value passes (NaN fails): a paired difference such as the coupled step's
  // extra cost per cell can come out negative on a loaded machine.
  m.expected = -std::numeric_limits<double>::infinity();
  m.comparison = io::Comparison::at_least;
  m.tolerance_reason =
      "informative: speed on a shared machine is never asserted; the metric only has to be a finite measurement";
  return m;
}

}  // namespace erythro::app
