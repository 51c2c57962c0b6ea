#pragma once
// Steady diffusion through a circular inclusion with a diffusivity jump (D_in inside radius a,
// D_out outside), exact solutions for the verification of curved-interface treatments
// (case verification.transport_curved_interface;
// docs/transport.md eqs T8–T10). Domain [−1, 1]², inclusion centred at the origin; both
// solutions are exact in a < r < R1 and blend smoothly to the side values in R1 < r < R2 < 1
// (χ(r) = 1 − S((r − R1)/(R2 − R1)), S the C⁴ quintic-to-nonic smoothstep), with the source
// that the blend needs written in the blend ring only (no cut node there), so the sides see
// exact data:
//  radial (the deoxygenation analogue: a cell releasing into a held medium): uniform source q0
//    inside, C_in = C_a + q0 (a² − r²)/(4 D_in); outside C' = −(q0 a²/(2 D_out)) χ(r)/r,
//    C = C_b for r ≥ R2 (all four sides fixed at C_b); blend source (q0 a²/2) χ'(r)/r.
//  dipole (a uniform gradient G x across an inclusion; tangential flux at the membrane):
//    C_in = G (1 + B) x, C_out = G x (1 + B a² χ(r)/r²), B = (D_out − D_in)/(D_out + D_in);
//    left/right sides fixed at ∓G, bottom/top zero flux; blend source
//    −D_out G B a² (χ'' − χ'/r) x/r².
// In both, C and D ∂C/∂r are continuous at r = a (checked by the unit of the case).
#include <string>
#include <vector>

#include "transport/subpixel_diffusivity.hpp"
#include "transport/transport_lattice.hpp"

namespace erythro::vv {

enum class InclusionProblem { radial, dipole };
// Treatment of the cut nodes: transport::InterfaceRule (transport/subpixel_diffusivity.hpp).
using InterfaceTreatment = transport::InterfaceRule;

struct Inclusion {
  InclusionProblem problem = InclusionProblem::radial;
  double a = 0.5, R1 = 0.7, R2 = 0.95;  // inclusion radius, blend ring
  double D_in = 950.0 / 2800.0, D_out = 1.0;
  double q0 = 1.0, C_b = 0.0, G = 1.0;
  double concentration(double x, double y) const;
  double source(double x, double y) const;  // −∇·(D∇C) (q0 inside, the blend ring's source)
  double scale() const;                       // C range for relative errors
  // D ∂C/∂r just inside and just outside r = a at angle θ (equal for an exact solution).
  double radial_flux(double theta, bool inside) const;
};

struct InclusionRun {
  int n = 0;                 // nodes per side
  double error_l2 = 0.0;     // RMS over all nodes of |Ĉ − C_exact| / scale (Ĉ: eq T7)
  double error_max = 0.0;    // max over all nodes
  double error_cut = 0.0;    // RMS over the cut nodes (0 < φ < 1)
  double error_bulk = 0.0;   // max over the nodes farther than 2h from the interface
  double error_bulk_in = 0.0;   // max over the inside nodes farther than 2h (r < a − 2h)
  double error_mean = 0.0;   // |Σ φ (Ĉ − C_exact)| / (Σ φ scale): the inclusion's mean (as P̄)
  long steps = 0;
  double worst_mass_residual = 0.0;
  double wall_s = 0.0;
  std::string scene_text;  // the scene as run (curved_interface.toml with the case's overrides)
};

// Steady TRT (Λ = 1/4) D2Q5 run on n × n nodes from the exact field (the scene
// curved_interface.toml); D_out in lattice units `D_out_lattice` (τ only changes how fast it
// settles: the steady TRT state depends on D and Λ).
InclusionRun run_inclusion(const Inclusion& p, int n, InterfaceTreatment t, double D_out_lattice = 0.5);

// The deoxygenation cell's steady analogue (no exact solution; docs/validation-deoxygenation.md):
// geometry::biconcave(800, 3.91 µm) centred in a box of half-width 6 µm held at 0, a uniform
// source inside (φ q at cut nodes), D_in/D_out = 950/2800; returns the φ-weighted mean of Ĉ
// (the case's P̄) in units of q L²/D_out at spacing h_um.
double biconcave_steady_mean(double h_um, InterfaceTreatment t);

}  // namespace erythro::vv
