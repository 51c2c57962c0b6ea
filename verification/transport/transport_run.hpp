#pragma once
// Shared driver of the transport V&V cases: time stepping with the mass balance
// (eq T5) checked after every step, steady-state detection, metric shorthands.
#include <functional>
#include <string>
#include <vector>

#include "io/result_record.hpp"
#include "transport/transport_lattice.hpp"

namespace erythro::vv {

struct TransportRun {
  long steps = 0;
  double wall_time_s = 0.0;
  double worst_mass_residual = 0.0;  // max over steps of |residual| / scale
  bool converged = true;             // steady runs: change below tolerance
};

// Tracks the worst relative mass-balance residual over the steps it is shown.
struct MassBalanceMonitor {
  double worst = 0.0;
  void observe(const transport::TransportLattice& lat);
};

// `before_step(lattice)` (optional) runs before every step, e.g. to set reactions.
using BeforeStep = std::function<void(transport::TransportLattice&)>;

// Steps `steps` times.
TransportRun run_steps(transport::TransportLattice& lat, long steps, const BeforeStep& before_step = {});

// Steps until the largest change of C over `interval` steps is at most `tolerance`
// (absolute), or max_steps (then converged = false).
TransportRun run_to_steady(transport::TransportLattice& lat, long interval, double tolerance, long max_steps,
                           const BeforeStep& before_step = {});

// Metric: worst relative mass-balance residual over every run of the case ≤ 1e-13.
io::Metric mass_balance_metric(double worst_relative_residual);

// Mean of C over each row (profiles of cases uniform in x).
std::vector<double> row_average(const transport::TransportLattice& lat);

}  // namespace erythro::vv
