#pragma once
// The metric of every `erythro bench` section: a measured speed, recorded with the
// comparison `at_least 0`, so the record holds it without ever asserting it.
#include <string>
#include <utility>

#include "io/result_record.hpp"

namespace erythro::app {

inline io::Metric informative(std::string name, std::string description, std::string unit, double value) {
  io::Metric m;
  m.name = std::move(name);
  m.description = std::move(description);
  m.unit = std::move(unit);
  m.value = value;
  m.expected = 0.0;
  m.comparison = io::Comparison::at_least;
  m.tolerance_reason =
      "informative: speed on a shared machine is never asserted; the metric only has to be a finite measurement";
  return m;
}

}  // namespace erythro::app
