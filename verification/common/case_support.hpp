#pragma once
// Small helpers shared by the V&V cases: timing, error norms, metric shorthands.
#include <chrono>
#include <string>
#include <vector>

#include "io/result_record.hpp"

namespace erythro::vv {

// printf-style formatting of one number: fmt("%.3g um", x).
std::string fmt(const char* format, double value);

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

// ‖a − b‖₂ / ‖b‖₂ over all entries (b must not vanish).
double relative_l2(const std::vector<double>& a, const std::vector<double>& b);
// max |a − b| / max |b|.
double relative_linf(const std::vector<double>& a, const std::vector<double>& b);

// One resolution of a study: its point (h, error) in the convergence series and its
// (wall time, error, label) in the speed-against-error series.
void add_convergence_point(io::ConvergenceSeries& series, io::SpeedErrorSeries& speed, double h, double error,
                           double wall_time_s, const std::string& label);

// Metric asserting an observed order: |p − formal| ≤ tolerance.
io::Metric order_metric(const io::ConvergenceSeries& series, const std::string& reason);
// Metric asserting the asymptotic-range check of a series (1 = in range).
io::Metric asymptotic_metric(const io::ConvergenceSeries& series);

}  // namespace erythro::vv
