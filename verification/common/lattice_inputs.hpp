#pragma once
// Scene values for a set-up designed in lattice units. A scene is written in physical
// units, which the solver converts (scene/units.cpp, scene/cell_checks.cpp); a case whose
// set-up is given in lattice units writes, for each value, the physical number that the
// solver's own conversion turns into exactly that lattice value, so the run is the
// lattice set-up bit for bit (round-trip of the %.17g overrides: scene_case.hpp).
#include <functional>
#include <string>
#include <vector>

#include "ib/kernel.hpp"
#include "membrane/membrane_energy.hpp"

namespace erythro::vv {

// The double x nearest `guess` (searched over the 64 doubles on either side) for which
// convert(x) == target exactly; `guess` when there is none.
double exact_input(double guess, double target, const std::function<double(double)>& convert);

// Overrides of `scene_file` (after `set_up`, which fixes h, Δt and ρ0) that set the
// membrane to `model` (lattice moduli, law neo-Hookean) with `kernel`.
std::vector<std::string> membrane_overrides(const std::string& scene_file, const std::vector<std::string>& set_up,
                                            ib::KernelType kernel, const membrane::MembraneModel& model);

// The override `key` (an angle in degrees, e.g. cells[0].angle_deg) that the solver turns
// into exactly `radians`.
std::string angle_override(const std::string& key, double radians);

// A length in µm that the solver turns into exactly `lattice` h with h = h_um (x_um / h_um,
// the conversion of cell radii and centres).
double length_um(double lattice, double h_um);

}  // namespace erythro::vv
