#pragma once
// Observed order of accuracy from a resolution study (used by every convergence case).
//
//  observed order p: least-squares slope of log(error) against log(h) over all levels;
//  local orders p_k = log(e_k/e_{k+1}) / log(h_k/h_{k+1}) between successive levels;
//  asymptotic-range check: the finest local order agrees with the formal order within
//  the case's tolerance (the error is in its asymptotic range there), and no local
//  order has the wrong sign (the error decreases with every refinement).
#include <string>
#include <vector>

#include "io/result_record.hpp"

namespace erythro::vv {

double least_squares_slope(const std::vector<double>& x, const std::vector<double>& y);

// Fills local_orders, observed_order, asymptotic and asymptotic_rule of a series
// whose h, error, formal_order and order_tolerance are set.
void fit_order(io::ConvergenceSeries& series);

// A quantity whose converged value is unknown: q(h) ≈ q0 + C h^p fitted to three or more levels in
// the least-squares sense (for each p on a grid of step 0.001 in [p_min, p_max], q0 and C by linear
// least squares; the p with the smallest residual kept). With three levels the fit is exact when an
// exact p exists in the range. `residual_rms` is the root mean square of q − q0 − C h^p.
struct LimitFit {
  double limit = 0.0, coefficient = 0.0, order = 0.0, residual_rms = 0.0;
};
LimitFit fit_limit_and_order(const std::vector<double>& h, const std::vector<double>& q, double p_min = 0.25,
                             double p_max = 4.0);

}  // namespace erythro::vv
