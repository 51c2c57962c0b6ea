#pragma once
// The steady-state test of verification.manufactured (manufactured_test.cpp) as a probe
// of the run, sampled once per chunk (output.diagnostics_interval_steps):
//   mms_error_u               ‖u − u_exact‖ / ‖u_exact‖ (both components, all nodes);
//   mms_transient_over_error  (‖u − u_prev‖ / ‖u_prev‖) / (e − 1) / mms_error_u, the
//                             remaining transient of an exponential decay over one e-fold
//                             chunk against the error being measured (NaN at the first
//                             chunk); [[stop_when]] in manufactured.toml ends the run on it.
// The sample at step 0 (the exact start) is not a chunk and is skipped (NaN).
#include <span>
#include <vector>

#include "simulation/probe.hpp"

namespace erythro::vv {

// sqrt(Σ|a − b|²/Σ|b|²) over both components of a vector field.
double relative_l2_vector(std::span<const double> ax, std::span<const double> ay, std::span<const double> bx,
                          std::span<const double> by);

class ManufacturedSteadyProbe : public sim::Probe {
 public:
  ManufacturedSteadyProbe(std::vector<double> exact_ux, std::vector<double> exact_uy)
      : exact_ux_(std::move(exact_ux)), exact_uy_(std::move(exact_uy)) {}

  void declare(std::vector<sim::SeriesInfo>& series) const override;
  void sample(const sim::ProbeContext& context, std::span<double> values) override;

 private:
  std::vector<double> exact_ux_, exact_uy_, previous_ux_, previous_uy_;
};

}  // namespace erythro::vv
