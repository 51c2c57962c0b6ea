#include "fluid_scenes.hpp"

#include <cmath>
#include <cstdio>

#include "common/lattice_inputs.hpp"
#include "common/scene_case.hpp"

namespace erythro::vv {

std::string set_grid(int nx, int ny) { return set("domain.size_um", double(nx), double(ny)); }

std::string set_collision(fluid::CollisionModel model) {
  return set("fluid.collision", "\"" + std::string(fluid::to_string(model)) + "\"");
}

std::string set_tau(const SceneFile& file, const std::vector<std::string>& overrides, double tau) {
  const scene::LatticeSetup s = file.setup(overrides);
  const double h = s.scales.length_m, dt = s.scales.time_s;
  const double mu_cP = (tau - 0.5) / 3.0 * h * h / dt * s.scales.density_kg_m3 * 1e3;
  return set_exact(file, overrides, "fluid.viscosity_cP", tau, mu_cP,
                   [](const scene::LatticeSetup& l) { return l.collision.tau; });
}

std::string set_exact(const SceneFile& file, const std::vector<std::string>& overrides, const std::string& key,
                      std::array<double, 2> target, const LatticeScalar& per_lattice, const LatticeVector& lattice_of) {
  const double scale = per_lattice(file.setup(overrides));
  std::array<double, 2> x{target[0] * scale, target[1] * scale};
  for (int c = 0; c < 2; ++c) {
    if (target[c] == 0.0) {
      x[c] = 0.0;
      continue;
    }
    x[c] = exact_input(x[c], target[c], [&](double v) {
      std::array<double, 2> trial = x;
      trial[c] = v;
      return lattice_of(file.setup(with(overrides, set(key, trial[0], trial[1]))))[c];
    });
    const double got = lattice_of(file.setup(with(overrides, set(key, x[0], x[1]))))[c];
    if (got != target[c])  // the run differs from the case's set-up by this round-off
      std::fprintf(stderr, "note: %s[%d]: lattice value %.17g, not %.17g exactly (rel %.1e)\n", key.c_str(), c, got,
                   target[c], std::abs(got / target[c] - 1.0));
  }
  return set(key, x[0], x[1]);
}

std::string set_exact(const SceneFile& file, const std::vector<std::string>& overrides, const std::string& key,
                      double target, double rough, const LatticeScalar& lattice_of) {
  const double x =
      exact_input(rough, target, [&](double v) { return lattice_of(file.setup(with(overrides, set(key, v)))); });
  const double got = lattice_of(file.setup(with(overrides, set(key, x))));
  if (got != target)
    std::fprintf(stderr, "note: %s: lattice value %.17g, not %.17g exactly (rel %.1e)\n", key.c_str(), got, target,
                 std::abs(got / target - 1.0));
  return set(key, x);
}

double um_s_per_lattice(const scene::LatticeSetup& s) { return s.scales.velocity_m_s() * 1e6; }
double N_m3_per_lattice(const scene::LatticeSetup& s) { return s.scales.force_density_N_m3(); }

std::string set_body_force(const SceneFile& file, const std::vector<std::string>& overrides,
                           std::array<double, 2> force) {
  return set_exact(file, overrides, "body_force.density_N_m3", force, N_m3_per_lattice,
                   [](const scene::LatticeSetup& s) { return s.body_force; });
}

std::string set_top_wall_velocity(const SceneFile& file, const std::vector<std::string>& overrides, double ux) {
  return set_exact(file, overrides, "boundaries.top.velocity_um_s", {ux, 0.0}, um_s_per_lattice,
                   [](const scene::LatticeSetup& s) { return std::array<double, 2>{s.boundaries.top.ux, 0.0}; });
}

std::string set_initial_velocity(const SceneFile& file, const std::vector<std::string>& overrides,
                                 std::array<double, 2> u) {
  return set_exact(file, overrides, "initial.velocity_um_s", u, um_s_per_lattice,
                   [](const scene::LatticeSetup& s) { return s.initial_velocity; });
}

}  // namespace erythro::vv
