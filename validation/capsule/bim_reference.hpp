#pragma once
// The capsule's boundary-integral reference (reference_data/capsule_bim/reference_capsule.csv,
// written by capsule_bim.py; PROVENANCE.md there): steady D, θ and tank-treading period of a
// capsule in unbounded simple shear at Re = 0, viscosity ratio 1, for each tension law and G.
#include <string>
#include <vector>

namespace erythro::vv {

struct BimReference {
  std::string law;         // "neo_hookean" or "hookean" (membrane.law)
  double G = 0;            // μγ̇a/E_s
  double D = 0;            // Taylor deformation
  double theta_deg = 0;    // inclination of the long axis to the flow
  double T_gamma = 0;      // tank-treading period × γ̇
};

// Every row of the CSV at `path`, in file order; columns found by their header names (law, G,
// D, theta_deg, T_gamma). Throws InputError naming the file when it is missing or malformed.
std::vector<BimReference> read_bim_reference(const std::string& path);

}  // namespace erythro::vv
