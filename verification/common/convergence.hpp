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

}  // namespace erythro::vv
