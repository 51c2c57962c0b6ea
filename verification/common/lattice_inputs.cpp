#include "lattice_inputs.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "common/scene_case.hpp"
#include "membrane/membrane_units.hpp"

namespace erythro::vv {

double exact_input(double guess, double target, const std::function<double(double)>& convert) {
  if (convert(guess) == target) return guess;
  double up = guess, down = guess;
  for (int k = 0; k < 64; ++k) {
    up = std::nextafter(up, std::numeric_limits<double>::infinity());
    if (convert(up) == target) return up;
    down = std::nextafter(down, -std::numeric_limits<double>::infinity());
    if (convert(down) == target) return down;
  }
  return guess;
}

std::vector<std::string> membrane_overrides(const std::string& scene_file, const std::vector<std::string>& set_up,
                                            ib::KernelType kernel, const membrane::MembraneModel& model) {
  // The solver's conversion (scene/cell_checks.cpp): SI, then membrane/membrane_units.hpp.
  const scene::UnitScales u = scene::derive_lattice(case_scene(scene_file, set_up)).scales;
  const membrane::LatticeScales ms{u.length_m, u.time_s, u.density_kg_m3};
  const double force = u.density_kg_m3 * u.length_m * u.length_m * u.length_m / (u.time_s * u.time_s);  // N/m
  const double Es = exact_input(model.tension.modulus * force / membrane::kDynPerCm, model.tension.modulus,
                                [&](double x) { return membrane::tension_to_lattice(x * membrane::kDynPerCm, ms); });
  const double EB = exact_input(model.bending * force * u.length_m * u.length_m / membrane::kDynCm, model.bending,
                                [&](double x) { return membrane::bending_to_lattice(x * membrane::kDynCm, ms); });
  const double kA = exact_input(model.area_modulus * force / u.length_m, model.area_modulus,
                                [&](double x) { return membrane::pressure_to_lattice(x, ms); });
  return {set("membrane.law", std::string("\"neo_hookean\"")),
          set("membrane.kernel", "\"" + std::string(ib::to_string(kernel)) + "\""),
          set("membrane.shear_modulus_dyn_cm", Es), set("membrane.bending_modulus_dyn_cm", EB),
          set("membrane.area_modulus_Pa", kA)};
}

std::string angle_override(const std::string& key, double radians) {
  return set(key, exact_input(radians * 180.0 / std::numbers::pi, radians,
                              [](double deg) { return deg * std::numbers::pi / 180.0; }));
}

double length_um(double lattice, double h_um) {
  return exact_input(lattice * h_um, lattice, [h_um](double x) { return x / h_um; });
}

}  // namespace erythro::vv
