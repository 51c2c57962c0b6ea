#include "transport/hb_kinetics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

namespace {

// S_new of eq H2 over dt at a frozen P, and its derivative in P: one pow and one expm1.
struct Relaxation {
  double S_new = 0.0, dS_dP = 0.0;
};
Relaxation relax(const HbParameters& p, double S, double P, double dt) {
  const double q = P > 0.0 ? std::pow(P / p.P50, p.n) : 0.0;  // (P/P50)ⁿ
  const double S_eq = q / (1.0 + q);
  const double rate = p.sigma * p.k_off / p.M;
  const double em1 = std::expm1(-rate * (1.0 + q) * dt);  // e^{−λdt} − 1, λ = rate (1 + q)
  const double dq = P > 0.0 ? p.n * q / P : 0.0;
  const double dS_eq = dq / ((1.0 + q) * (1.0 + q));
  return {S - (S_eq - S) * em1, -dS_eq * em1 + (S_eq - S) * (1.0 + em1) * dt * rate * dq};
}

}  // namespace

HbStep advance_saturation_cell_implicit(const HbParameters& p, double S, double P_mean_torr, double dt) {
  if (!(p.M > 0.0)) throw std::invalid_argument("advance_saturation: rate modifier M must be > 0");
  // F(x) = x − S_new(S, P(x)), P(x) = P + C_heme (S − x)/α: the root lies between S and S_eq(P)
  // (F(S) has the sign of S − S_eq(P), F(S_eq(P)) the opposite). Newton from x = S, where the
  // root nearly is (the heme buffer keeps a step's change small), kept inside that bracket
  // (bisection when a step would leave it): 3–4 evaluations to round-off, where bisection took
  // ~50 (the local kinetics solve this once per heme node and step).
  const double buffer = p.C_heme / p.alpha;  // Torr per unit S
  const double S_eq = hill_saturation(P_mean_torr, p.P50, p.n);
  double near = S, far = S_eq;  // the bracket's ends: F(near) has the sign of F(S)
  double x = S, sign_near = 0.0;
  for (int it = 0; it < 100; ++it) {
    const Relaxation r = relax(p, S, P_mean_torr + buffer * (S - x), dt);
    const double F = x - r.S_new;
    if (std::abs(F) <= 2.0 * std::numeric_limits<double>::epsilon()) break;  // F at its rounding level
    if (it == 0) sign_near = F;
    if ((F < 0.0) == (sign_near < 0.0)) near = x;
    else far = x;
    const double lo = std::min(near, far), hi = std::max(near, far);
    double next = x - F / (1.0 + buffer * r.dS_dP);  // F'(x) = 1 + (C_heme/α) ∂S_new/∂P
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == x || next <= lo || next >= hi) break;  // bracket at round-off
    x = next;
  }
  return {x, p.C_heme * (S - x)};
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
