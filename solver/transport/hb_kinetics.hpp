#pragma once
// Haemoglobin–O2 kinetics of one red blood cell (docs/transport.md §4.2; thesis ch. V;
// docs/parameters.md "Haemoglobin and O2 release"). Units: Torr, µM, s (any consistent
// set works: k_off·dt is all that enters the update).
#include <cstddef>
#include <span>

namespace erythro::transport {

// Hill saturation S = Pⁿ / (Pⁿ + P50ⁿ) (Severinghaus; docs/parameters.md), P ≥ 0.
double hill_saturation(double P_torr, double P50 = 26.8, double n = 2.7);

struct HbParameters {
  double k_off = 44.0;     // HbO2 dissociation rate, 1/s (Eggleton et al. 2000)
  double C_heme = 20.3e3;  // heme concentration inside the RBC, µM (20.3 mM)
  double alpha = 1.3;      // O2 solubility, µM/Torr
  double P50 = 26.8;       // Torr
  double n = 2.7;          // Hill exponent
  double M = 1.0;          // calibrated rate modifier (> 0) in the rate's denominator (M < 1: faster)
  double sigma = 1.0;      // shear-stress coefficient σ(τ_RBC) multiplying the rate (ch. VI; 1 = off)
};

// Effective first-order rate of eq H1 at mean P: λ = σ k_off (1 + (P/P50)ⁿ) / M.
double hb_relaxation_rate(const HbParameters& p, double P_torr);

struct HbStep {
  double saturation = 0.0;  // S after the step
  double released = 0.0;    // O2 released per unit cell volume, µM: C_heme (S_old − S_new)
};

// Advances the cell-averaged saturation over dt (eq H1):
//   dS/dt = −(σ k_off / M) [S − (1 − S)(P/P50)ⁿ],
// with P (mean O2 partial pressure over the cell's interior nodes) frozen over the
// step. The ODE is then linear, dS/dt = −λ (S − S_eq), S_eq = hill_saturation(P), and
// the update is its EXACT solution (H2):
//   S_new = S_eq + (S − S_eq) e^{−λ dt}
// — unconditionally stable, monotone, never overshoots S_eq however stiff λ dt is.
// released is computed from the same two numbers, so bound + free O2 balance exactly.
HbStep advance_saturation(const HbParameters& p, double S, double P_mean_torr, double dt);

// Cell-implicit variant (H3): the P of the update is that at the END of the step, with
// the cell's own release kept in its interior, P_end = P + C_heme (S − S_new)/α:
//   S_new = S_eq(P_end) + (S − S_eq(P_end)) e^{−λ(P_end) dt},
// solved by bisection between S and S_eq(P) (the residual is monotone) to round-off.
// Why: the released O2 raises P, which raises S_eq; through the steep Hill curve the
// coupled relaxation runs at λ_eff ≈ λ (1 + C_heme S_eq'(P)/α), ~80 λ at 10–90 Torr.
// Lagging P by a step (advance_saturation with the previous P) is then stable only for
// λ_eff dt ≲ 2 (measured: verification.transport_hb_coupling); this variant is stable
// for any dt. Both are first order in dt when coupled to transport.
HbStep advance_saturation_cell_implicit(const HbParameters& p, double S, double P_mean_torr, double dt);

// Mean partial pressure C/α over the given nodes (concentration field in µM).
double mean_partial_pressure(std::span<const std::size_t> nodes, std::span<const double> concentration,
                             double alpha);

// Adds `released` (concentration per step) to source[n] for every listed node: the
// cell's release spread uniformly over its interior (total = nodes.size() · released).
void distribute_release(std::span<const std::size_t> nodes, double released, std::span<double> source);

}  // namespace erythro::transport
