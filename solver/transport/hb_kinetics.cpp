#include "transport/hb_kinetics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace erythro::transport {

double hill_saturation(double P_torr, double P50, double n) {
  if (!(P_torr > 0.0)) return 0.0;
  // S = 1 / (1 + (P50/P)ⁿ): no overflow of Pⁿ for large P.
  return 1.0 / (1.0 + std::pow(P50 / P_torr, n));
}

double hb_relaxation_rate(const HbParameters& p, double P_torr) {
  const double r = P_torr > 0.0 ? std::pow(P_torr / p.P50, p.n) : 0.0;
  return p.sigma * p.k_off * (1.0 + r) / p.M;
}

HbStep advance_saturation(const HbParameters& p, double S, double P_mean_torr, double dt) {
  if (!(p.M > 0.0)) throw std::invalid_argument("advance_saturation: rate modifier M must be > 0");
  if (!(dt >= 0.0)) throw std::invalid_argument("advance_saturation: dt must be non-negative");
  const double S_eq = hill_saturation(P_mean_torr, p.P50, p.n);
  const double lambda = hb_relaxation_rate(p, P_mean_torr);
  // Exact solution of the frozen-P linear ODE (H2). expm1 keeps small λdt accurate:
  // S_new − S = (S_eq − S)(1 − e^{−λdt}) = −(S_eq − S) expm1(−λdt).
  const double dS = -(S_eq - S) * std::expm1(-lambda * dt);
  const double S_new = S + dS;
  return {S_new, -p.C_heme * dS};
}

HbStep advance_saturation_cell_implicit(const HbParameters& p, double S, double P_mean_torr, double dt) {
  // F(x) = x − S_new(S, P + C_heme (S − x)/α): increasing in x (a lower x releases more,
  // raises P and S_eq), F(S) has the sign of S − S_eq(P) and F(S_eq(P)) the opposite.
  const auto F = [&](double x) {
    return x - advance_saturation(p, S, P_mean_torr + p.C_heme * (S - x) / p.alpha, dt).saturation;
  };
  const double Seq = hill_saturation(P_mean_torr, p.P50, p.n);
  double lo = std::min(S, Seq), hi = std::max(S, Seq);
  double flo = F(lo);
  for (int it = 0; it < 200 && hi - lo > 0.0; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;  // interval at round-off
    const double fm = F(mid);
    if ((fm < 0.0) == (flo < 0.0)) {
      lo = mid;
      flo = fm;
    } else {
      hi = mid;
    }
  }
  const double S_new = 0.5 * (lo + hi);
  return {S_new, p.C_heme * (S - S_new)};
}

double mean_partial_pressure(std::span<const std::size_t> nodes, std::span<const double> concentration,
                             double alpha) {
  if (nodes.empty()) return 0.0;
  double sum = 0.0;
  for (std::size_t n : nodes) sum += concentration[n];
  return sum / (static_cast<double>(nodes.size()) * alpha);
}

void distribute_release(std::span<const std::size_t> nodes, double released, std::span<double> source) {
  for (std::size_t n : nodes) source[n] += released;
}

}  // namespace erythro::transport
