#pragma once
// The error of a decaying Taylor–Green vortex against the exact solution (case
// verification.taylor_green, taylor_green_test.cpp), as a probe of the run: series
//   tg_error_u, tg_error_p           relative L2 velocity / pressure error at the sample,
//   tg_window_error_u, tg_window_error_p
//                                    relative L2 over the nodes and over every step of
//                                    t ∈ [¾T, T] (its own stage sums them after each step
//                                    of the window; complete at the last sample, NaN before).
// Exact: u·e^{−2νk²t}, p·e^{−4νk²t} of the t = 0 fields (p = c_s²(ρ − 1)), lattice units.
#include <vector>

#include "fluid/fluid_lattice.hpp"
#include "fluid/initial_state.hpp"
#include "simulation/probe.hpp"

namespace erythro::vv {

class TaylorGreenErrorProbe : public sim::Probe {
 public:
  // `exact0`: the exact fields at t = 0; ν, k the decay's viscosity and wavenumber;
  // `steps` = T.
  TaylorGreenErrorProbe(const fluid::FluidLattice& lattice, fluid::FlowField exact0, double nu, double k, long steps);

  void declare(std::vector<sim::SeriesInfo>& series) const override;
  void sample(const sim::ProbeContext& context, std::span<double> values) override;
  void register_stages(sim::TimeLoop& loop) override;

 private:
  struct Sums {
    double du2 = 0, u2 = 0, dp2 = 0, p2 = 0;
  };
  Sums sums(const fluid::Moments& m, long s) const;

  const fluid::FluidLattice& lattice_;
  fluid::FlowField exact0_;
  double nu_ = 0, k_ = 0;
  long steps_ = 0;
  Sums window_;
  long window_samples_ = 0;
};

}  // namespace erythro::vv
