// [time_mapping] (docs/model.md §10, eq 10.8): the density that sets the particle Reynolds
// number, its sources of γ̇ and a, its refusals, and the equivalence of the two readings of the
// thesis's mapping: a raised density at the physical shear rate gives the same lattice values as
// the shear rate and the moduli raised by the same factor at the physical density.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "input_error_matchers.hpp"
#include "scene/scene_parser.hpp"
#include "scene/units.hpp"

namespace erythro::scene {
namespace {

using testing::error_of;

// One circular capsule (a = 3 µm) in a 24 × 24 µm box at h = 0.5 µm, plasma 1.2 cP at
// 1025 kg/m³, between walls moving at ∓U (γ̇ = 2U/H = 100 1/s); `extra` is appended.
std::string shear_scene(double wall_um_s, double shear_modulus_dyn_cm, double bending_dyn_cm, double area_Pa,
                        const std::string& extra) {
  const auto n = [](double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return std::string(b);
  };
  return "[domain]\nsize_um = [24.0, 24.0]\nspacing_um = 0.5\n[time]\ntau = 1.0\n"
         "[fluid]\ndensity_kg_m3 = 1025.0\nviscosity_cP = 1.2\n"
         "[boundaries.bottom]\ntype = \"moving_wall\"\nvelocity_um_s = [" + n(-wall_um_s) + ", 0.0]\n"
         "[boundaries.top]\ntype = \"moving_wall\"\nvelocity_um_s = [" + n(wall_um_s) + ", 0.0]\n"
         "[initial]\ntype = \"shear\"\n[run]\nsteps = 10\n"
         "[membrane]\nshear_modulus_dyn_cm = " + n(shear_modulus_dyn_cm) + "\nbending_modulus_dyn_cm = " +
         n(bending_dyn_cm) + "\narea_modulus_Pa = " + n(area_Pa) +
         "\n[limits]\nmembrane_stability = \"warn\"\n"
         "[[cells]]\nshape = \"circle\"\nradius_um = 3.0\ncenter_um = [12.0, 12.0]\n" + extra;
}
constexpr double kWallUmS = 1200.0;  // γ̇ = 2 × 1200 µm/s / 24 µm = 100 1/s
constexpr double kEs = 6e-3, kEb = 1.8e-12, kKa = 200.0;

LatticeSetup derive(const std::string& text) { return derive_lattice(parse_scene(text, "mapping.toml")); }

// `text` with its walls of `type` at rest (no velocity lines) and the fluid starting at rest.
std::string still_sides(std::string text, const std::string& type) {
  for (const char* side : {"bottom", "top"}) {
    const std::string from = std::string("[boundaries.") + side + "]\ntype = \"moving_wall\"\n";
    const std::size_t at = text.find(from);
    const std::size_t end = text.find('\n', at + from.size());  // the velocity line
    text.replace(at, end + 1 - at, std::string("[boundaries.") + side + "]\ntype = \"" + type + "\"\n");
  }
  text.replace(text.find("type = \"shear\""), 14, "type = \"rest\"");
  return text;
}

TEST(TimeMapping, DensityFromTheReynoldsNumberOfTheWalls) {
  const LatticeSetup L = derive(shear_scene(kWallUmS, kEs, kEb, kKa, "[time_mapping]\nreynolds = 0.1\n"));
  ASSERT_TRUE(L.time_mapping.has_value());
  const TimeMapping& m = *L.time_mapping;
  const double mu = 1.2e-3, gamma = 100.0, a = 3e-6;
  EXPECT_DOUBLE_EQ(m.shear_rate_per_s, gamma);
  EXPECT_DOUBLE_EQ(m.radius_m, a);
  EXPECT_NEAR(m.run_density_kg_m3, 0.1 * mu / (gamma * a * a), 1e-12 * m.run_density_kg_m3);  // eq 10.8
  EXPECT_NEAR(m.physical_reynolds, gamma * a * a * 1025.0 / mu, 1e-15);
  EXPECT_DOUBLE_EQ(L.scales.density_kg_m3, m.run_density_kg_m3);
  // The lattice's own particle Reynolds number γ̇_lat a_lat²/ν_lat is the scene's.
  const double gamma_lat = gamma * L.scales.time_s, a_lat = a / L.scales.length_m;
  EXPECT_NEAR(gamma_lat * a_lat * a_lat / L.viscosity, 0.1, 1e-12);
  const std::string report = format_lattice_report(parse_scene(shear_scene(kWallUmS, kEs, kEb, kKa,
                                                                            "[time_mapping]\nreynolds = 0.1\n"),
                                                               "mapping.toml"),
                                                   L);
  EXPECT_CONTAINS(report, "time mapping");
}

// The thesis's reading: γ̇ and every modulus × k at the physical density. The same lattice.
TEST(TimeMapping, RaisedDensityEqualsRaisedShearRateWithScaledModuli) {
  const LatticeSetup mapped = derive(shear_scene(kWallUmS, kEs, kEb, kKa, "[time_mapping]\nreynolds = 0.1\n"));
  const double k = mapped.time_mapping->density_factor();
  const LatticeSetup raised = derive(shear_scene(k * kWallUmS, k * kEs, k * kEb, k * kKa, ""));
  const auto same = [](double x, double y) { return std::abs(x - y) <= 1e-13 * std::max(std::abs(x), std::abs(y)); };
  EXPECT_TRUE(same(mapped.collision.tau, raised.collision.tau));
  EXPECT_TRUE(same(mapped.boundaries.top.ux, raised.boundaries.top.ux)) << mapped.boundaries.top.ux;
  EXPECT_TRUE(same(mapped.boundaries.bottom.ux, raised.boundaries.bottom.ux));
  const auto& a = mapped.membrane->model;
  const auto& b = raised.membrane->model;
  EXPECT_TRUE(same(a.tension.modulus, b.tension.modulus)) << a.tension.modulus << " " << b.tension.modulus;
  EXPECT_TRUE(same(a.bending, b.bending));
  EXPECT_TRUE(same(a.area_modulus, b.area_modulus));
  EXPECT_EQ(mapped.total_steps, raised.total_steps);
  // The clocks: the mapped run's Δt is k times the raised one's, so its strain γ̇t is physical.
  EXPECT_TRUE(same(mapped.scales.time_s, k * raised.scales.time_s));
}

TEST(TimeMapping, ChannelShearRateFromTheBodyForce) {
  // Walls at rest, a steady force along x: γ̇ = F H/(2μ) (the plasma's wall shear rate).
  const std::string text = still_sides(shear_scene(0.0, kEs, kEb, kKa, "[body_force]\ndensity_N_m3 = [1.0e4, 0.0]\n"
                                                                    "[time_mapping]\nreynolds = 0.05\n"),
                                        "wall");
  const LatticeSetup L = derive(text);
  EXPECT_NEAR(L.time_mapping->shear_rate_per_s, 1.0e4 * 24e-6 / (2.0 * 1.2e-3), 1e-12);
}

TEST(TimeMapping, RefusesWhatItCannotMap) {
  const std::string base = shear_scene(kWallUmS, kEs, kEb, kKa, "");
  // Below the physical Re (γ̇a²ρ/μ = 7.7e-4 here): the mapping would lower the density.
  std::string e = error_of([&] { derive(base + "[time_mapping]\nreynolds = 0.0005\n"); });
  EXPECT_CONTAINS(e, "time_mapping.reynolds");
  EXPECT_CONTAINS(e, "0.00076875");
  // No drive to take γ̇ from: a periodic box without a force.
  const std::string periodic = still_sides(base, "periodic");
  e = error_of([&] { derive(periodic + "[time_mapping]\nreynolds = 0.1\n"); });
  EXPECT_CONTAINS(e, "time_mapping.shear_rate_per_s");
  EXPECT_NO_THROW(derive(periodic + "[time_mapping]\nreynolds = 0.1\nshear_rate_per_s = 100.0\n"));
  // No cells to take a from.
  std::string no_cells = base.substr(0, base.find("[[cells]]"));
  e = error_of([&] { derive(no_cells + "[time_mapping]\nreynolds = 0.1\n"); });
  EXPECT_CONTAINS(e, "time_mapping.radius_um");
  EXPECT_NO_THROW(derive(no_cells + "[time_mapping]\nreynolds = 0.1\nradius_um = 3.0\n"));
  // The key is required.
  e = error_of([&] { derive(base + "[time_mapping]\nradius_um = 3.0\n"); });
  EXPECT_CONTAINS(e, "missing key 'time_mapping.reynolds'");
}

}  // namespace
}  // namespace erythro::scene
