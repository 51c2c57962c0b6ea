// [membrane] and [[cells]]: parsing, conversion of the moduli, placement of the
// shapes, and every set-up rejection (overlap, wall, resolution, marker spacing,
// explicit-membrane stability).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "aggregation/morse_units.hpp"
#include "common/error.hpp"
#include "geometry/polygon.hpp"
#include "geometry/shapes.hpp"
#include "membrane/membrane_units.hpp"
#include "input_error_matchers.hpp"
#include "scene/scene_parser.hpp"
#include "scene/units.hpp"
#include "scene_fixtures.hpp"

namespace erythro::scene {
namespace {

using testing::channel_scene;
using testing::derive;
using testing::error_of;

// 20 µm × 10 µm channel, h = 0.5 µm (40 × 20 nodes), walls at bottom and top, τ = 1.
// ν = 1 cP / 1000 kg/m³ = 1e-6 m²/s → Δt = ½ h² / (3ν) = 0.5 · 0.25e-12 / 3e-6 = 4.1667e-8 s.
const std::string channel = channel_scene("20, 10", "0.5", "1.0", "10");

const std::string membrane_table = R"(
[membrane]
law = "neo_hookean"
shear_modulus_dyn_cm = 6e-3
bending_modulus_dyn_cm = 2e-12
area_modulus_Pa = 10.0
kernel = "peskin4"
)";

std::string cell(const std::string& body) { return "\n[[cells]]\n" + body + "\n"; }
const std::string circle_at_centre = cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [10, 5]\nmarkers = 32");


TEST(SceneCells, AbsentMeansFluidOnly) {
  const Scene s = parse_scene(channel, "c.toml");
  EXPECT_FALSE(s.membrane.has_value());
  EXPECT_TRUE(s.cells.empty());
  EXPECT_FALSE(derive_lattice(s).membrane.has_value());
}

TEST(SceneCells, ParsesEveryKey) {
  const Scene s = parse_scene(channel + membrane_table +
                                  cell("shape = \"ellipse\"\nsemi_axes_um = [3, 1.5]\ncenter_um = [6, 5]\n"
                                       "angle_deg = 30\nscale = 1.1\nmarkers = 40") +
                                  cell("shape = \"biconcave\"\nradius_um = 2.5\ncenter_um = [14, 5]\nmarkers = 48"),
                              "c.toml");
  ASSERT_TRUE(s.membrane.has_value());
  EXPECT_EQ(s.membrane->law, "neo_hookean");
  EXPECT_DOUBLE_EQ(s.membrane->shear_modulus_dyn_cm, 6e-3);
  EXPECT_DOUBLE_EQ(s.membrane->bending_modulus_dyn_cm, 2e-12);
  EXPECT_DOUBLE_EQ(s.membrane->area_modulus_Pa, 10.0);
  EXPECT_EQ(s.membrane->kernel, "peskin4");
  ASSERT_EQ(s.cells.size(), 2u);
  EXPECT_EQ(s.cells[0].shape, "ellipse");
  EXPECT_DOUBLE_EQ(s.cells[0].semi_axes_um[1], 1.5);
  EXPECT_DOUBLE_EQ(s.cells[0].angle_deg, 30.0);
  EXPECT_DOUBLE_EQ(s.cells[0].scale, 1.1);
  EXPECT_EQ(s.cells[0].markers, 40);
  EXPECT_EQ(s.cells[1].shape, "biconcave");
  EXPECT_DOUBLE_EQ(s.cells[1].center_um[0], 14.0);
}

TEST(SceneCells, ModuliUseTheMembraneLayerConversion) {
  const LatticeSetup L = derive(channel + membrane_table + circle_at_centre);
  ASSERT_TRUE(L.membrane.has_value());
  const double dt = 0.5 * 0.25e-12 / 3e-6, h = 0.5e-6, rho = 1000.0;
  // E_s: 6e-3 dyn/cm = 6e-6 N/m → × Δt²/(ρ h³); E_B: 2e-12 dyn·cm = 2e-19 J → × Δt²/(ρ h⁵);
  // k_A: 10 Pa → × Δt²/(ρ h²) (membrane_units.hpp).
  EXPECT_NEAR(L.membrane->model.tension.modulus, 6e-6 * dt * dt / (rho * h * h * h), 1e-12 * 1e-4);
  EXPECT_NEAR(L.membrane->model.bending / (2e-19 * dt * dt / (rho * std::pow(h, 5))), 1.0, 1e-12);
  EXPECT_NEAR(L.membrane->model.area_modulus / (10.0 * dt * dt / (rho * h * h)), 1.0, 1e-12);
  EXPECT_EQ(L.membrane->kernel, ib::KernelType::peskin4);
  EXPECT_EQ(L.membrane->model.tension.type, membrane::TensionLawType::neo_hookean);
}

TEST(SceneCells, ShapesArePlacedRotatedAndScaled) {
  const LatticeSetup L = derive(channel + membrane_table +
                                cell("shape = \"ellipse\"\nsemi_axes_um = [3, 1.5]\ncenter_um = [6, 5]\n"
                                     "angle_deg = 90\nscale = 1.2\nmarkers = 48") +
                                cell("shape = \"biconcave\"\nradius_um = 3.0\ncenter_um = [14, 5]\nmarkers = 48"));
  ASSERT_EQ(L.membrane->cells.size(), 2u);
  const geometry::Polygon& e = L.membrane->cells[0].shape;
  double cx = 0.0, cy = 0.0;
  geometry::centroid(e, cx, cy);
  EXPECT_NEAR(cx, 12.0, 1e-9);  // 6 µm / 0.5 µm
  EXPECT_NEAR(cy, 10.0, 1e-9);
  // Rotated by 90°: the long semi-axis 3 µm × 1.2 = 7.2 h lies along y.
  double ymax = -1e9, xmax = -1e9;
  for (std::size_t m = 0; m < e.size(); ++m) {
    ymax = std::max(ymax, e.y[m] - cy);
    xmax = std::max(xmax, e.x[m] - cx);
  }
  EXPECT_NEAR(ymax, 7.2, 0.05);
  EXPECT_NEAR(xmax, 3.6, 0.05);
  // Ellipse area π a b (polygon inscribed: slightly less).
  EXPECT_NEAR(geometry::signed_area(e) / (std::numbers::pi * 7.2 * 3.6), 1.0, 0.01);
  // Evans–Fung section: long axis 2a = 12 h along x.
  const geometry::Polygon& b = L.membrane->cells[1].shape;
  const auto [lo, hi] = std::minmax_element(b.x.begin(), b.x.end());
  EXPECT_NEAR(*hi - *lo, 12.0, 0.05);
  EXPECT_GT(geometry::signed_area(b), 0.0);  // counter-clockwise
}

// cells.prestretch λ: the rest shape is the unplaced shape scaled by 1/λ (a pre-stressed
// membrane); without it the rest shape is the placed shape itself (CellSetup::rest empty).
TEST(SceneCells, PrestretchGivesASmallerRestShape) {
  const LatticeSetup L = derive(channel + cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [10, 5]\n"
                                               "angle_deg = 30\nmarkers = 32\nprestretch = 1.05"));
  const CellSetup& c = L.membrane->cells[0];
  ASSERT_EQ(c.rest.size(), c.shape.size());
  // Rest circle of radius 4 h / 1.05, centred at the origin, marker 0 on +x.
  const geometry::Polygon rest = geometry::circle(32, 2.0 / 0.5 / 1.05);
  EXPECT_EQ(c.rest.x, rest.x);
  EXPECT_EQ(c.rest.y, rest.y);
  EXPECT_NEAR(geometry::perimeter(c.shape) / geometry::perimeter(c.rest), 1.05, 1e-12);
  EXPECT_TRUE(derive(channel + circle_at_centre).membrane->cells[0].rest.x.empty());
  // The stability estimate takes the largest stiffness dT/dλ up to the largest prestretch
  // (Skalak's grows with λ; the neo-Hookean's is largest at λ = 1).
  const std::string skalak = "[membrane]\nlaw = \"skalak\"\n";
  const LatticeSetup stiff = derive(channel + skalak + cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [10, 5]\n"
                                                            "markers = 32\nprestretch = 1.5"));
  EXPECT_GT(stiff.membrane->stability.tension_number,
            derive(channel + skalak + circle_at_centre).membrane->stability.tension_number);
  EXPECT_CONTAINS(error_of([] { derive(channel + cell("shape = \"circle\"\nradius_um = 2\ncenter_um = [10, 5]\n"
                                                      "markers = 32\nprestretch = 0.9")); }),
                  "key 'cells[0].prestretch' = 0.9 is out of range: must be in [1, 2]");
}

// Without `markers`: perimeter / 0.7 h. Circle of radius 4 h: ⌈2π·4 / 0.7⌉ = ⌈35.9⌉ = 36;
// radius 2 µm with scale 1.5 (6 h): ⌈2π·6 / 0.7⌉ = ⌈53.9⌉ = 54.
TEST(SceneCells, MarkerCountIsAutomaticWhenAbsent) {
  const LatticeSetup L = derive(channel + cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [5, 5]") +
                                cell("shape = \"circle\"\nradius_um = 2.0\nscale = 1.5\ncenter_um = [14, 5]"));
  EXPECT_EQ(L.membrane->cells[0].shape.size(), 36u);
  EXPECT_EQ(L.membrane->cells[1].shape.size(), 54u);
  EXPECT_LE(L.membrane->cells[0].max_edge, kMaxMarkerSpacing);
  EXPECT_GE(L.membrane->cells[0].min_edge, kMinMarkerSpacing);
}

TEST(SceneCells, CheckReportShowsLatticeAndStabilityNumbers) {
  const Scene s = parse_scene(channel + membrane_table + circle_at_centre, "c.toml");
  const std::string report = format_lattice_report(s, derive_lattice(s));
  EXPECT_CONTAINS(report, "stability Π_T");
  EXPECT_CONTAINS(report, "stability Π_B");
  EXPECT_CONTAINS(report, "cell 0 (circle)");
  EXPECT_CONTAINS(report, "32 markers");
}

TEST(SceneCells, UnknownAndMistypedKeysAreErrors) {
  EXPECT_CONTAINS(error_of([] { derive(channel + cell("shape = \"circle\"\nradius_mu = 2\ncenter_um = [10, 5]")); }),
                  "unknown key 'cells[0].radius_mu' (did you mean 'cells.radius_um'?)");
  EXPECT_CONTAINS(error_of([] { derive(channel + "[membrane]\nshear_modulus = 1\n"); }),
                  "unknown key 'membrane.shear_modulus'");
  EXPECT_CONTAINS(error_of([] { derive("cells = 3\n" + channel); }), "expected an array of tables");
  EXPECT_CONTAINS(error_of([] { derive(channel + "[membrane]\nlaw = \"mooney\"\n"); }), "membrane.law");
  EXPECT_CONTAINS(error_of([] { derive(channel + "[membrane]\nkernel = \"gauss\"\n"); }), "membrane.kernel");
  EXPECT_CONTAINS(error_of([] { derive(channel + "[membrane]\nshear_modulus_dyn_cm = -1\n"); }),
                  "membrane.shear_modulus_dyn_cm");
  EXPECT_CONTAINS(error_of([] { derive(channel + "[membrane]\nskalak_c = 2\n"); }), "membrane.skalak_c");
  EXPECT_CONTAINS(error_of([] { derive(channel + cell("shape = \"square\"\nradius_um = 2\ncenter_um = [10, 5]")); }),
                  "cells[0].shape");
  EXPECT_CONTAINS(error_of([] { derive(channel + cell("shape = \"circle\"\nradius_um = 2\ncenter_um = [10, 5]\nmarkers = 4.5")); }),
                  "cells[0].markers");
  EXPECT_CONTAINS(error_of([] { derive(channel + cell("shape = \"circle\"\ncenter_um = [10, 5]")); }),
                  "missing key 'cells[0].radius_um'");
  EXPECT_CONTAINS(error_of([] { derive(channel + cell("shape = \"ellipse\"\nradius_um = 2\nsemi_axes_um = [2, 1]\ncenter_um = [10, 5]")); }),
                  "cells[0].radius_um");
  EXPECT_CONTAINS(error_of([] { derive(channel + cell("shape = \"circle\"\nradius_um = 2")); }),
                  "missing key 'cells[0].center_um'");
  EXPECT_CONTAINS(error_of([] { derive(channel + circle_at_centre, {"cells.radius_um=3"}); }),
                  "addressed by index, e.g. --set cells[0].radius_um=3");
  EXPECT_CONTAINS(error_of([] { derive(channel + circle_at_centre, {"cells[1].radius_um=3"}); }),
                  "the scene has 1 [[cells]] entries (index 0 … 0)");
  EXPECT_CONTAINS(error_of([] { derive(channel + circle_at_centre, {"cells[x].radius_um=3"}); }),
                  "addressed by index");
  // An index too large for any integer type is past the end, not an internal error.
  EXPECT_CONTAINS(error_of([] { derive(channel + circle_at_centre, {"cells[99999999999999999999].radius_um=2"}); }),
                  "the scene has 1 [[cells]] entries (index 0 … 0)");
  // An override goes through the same checks as the file: range, then overlap.
  EXPECT_CONTAINS(error_of([] { derive(channel + circle_at_centre, {"cells[0].radius_um=-1"}); }),
                  "cells[0].radius_um");
}

TEST(SceneCells, SetOverridesAnEntryByIndex) {
  const std::string two = channel + circle_at_centre + cell("shape = \"circle\"\nradius_um = 1.5\ncenter_um = [4, 5]\nmarkers = 32");
  const std::vector<std::string> set = {"cells[1].radius_um=1.6", "cells[0].center_um=[12, 5]"};
  const Scene s = parse_scene(two, "c.toml", set);
  ASSERT_EQ(s.cells.size(), 2u);
  EXPECT_DOUBLE_EQ(s.cells[1].radius_um, 1.6);
  EXPECT_DOUBLE_EQ(s.cells[1].center_um[0], 4.0);  // untouched
  EXPECT_DOUBLE_EQ(s.cells[0].center_um[0], 12.0);
  EXPECT_DOUBLE_EQ(s.cells[0].radius_um, 2.0);
  EXPECT_NO_THROW(derive(two, set));
}

TEST(SceneCells, RejectsOverlappingCells) {
  const std::string msg = error_of([] {
    derive(channel + circle_at_centre + cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [13, 5]\nmarkers = 32"));
  });
  EXPECT_CONTAINS(msg, "key 'cells[1].center_um' = [13, 5]");
  EXPECT_CONTAINS(msg, "overlap cell 0");
  // A small cell wholly inside a larger one.
  EXPECT_CONTAINS(error_of([] {
                    derive(channel + cell("shape = \"circle\"\nradius_um = 4.0\ncenter_um = [10, 5]\nmarkers = 64") +
                           cell("shape = \"circle\"\nradius_um = 1.6\ncenter_um = [10, 5]\nmarkers = 24"));
                  }),
                  "one lies inside the other");
  // Across the periodic x boundary: centres 0.5 µm and 19.5 µm are 1 µm apart.
  EXPECT_CONTAINS(error_of([] {
                    derive(channel + cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [0.5, 5]\nmarkers = 32") +
                           cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [19.5, 5]\nmarkers = 32"));
                  }),
                  "overlap cell 0");
  // 2 h of clearance is accepted.
  EXPECT_NO_THROW(derive(channel + circle_at_centre +
                         cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [15.5, 5]\nmarkers = 32")));
  // Rims 0.3 µm = 0.6 h apart: rejected by default, accepted with limits.min_cell_gap = 0.5
  // (an aggregated pair at its contact gap on a coarse lattice).
  const std::string close = cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [14.3, 5]\nmarkers = 32");
  EXPECT_CONTAINS(error_of([&] { derive(channel + circle_at_centre + close); }), "(limits.min_cell_gap)");
  EXPECT_NO_THROW(derive(channel + "[limits]\nmin_cell_gap = 0.5\n" + circle_at_centre + close));
}

TEST(SceneCells, RejectsCellsOnAWallOrOutside) {
  const std::string msg = error_of([] { derive(channel + cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [10, 2.2]\nmarkers = 32")); });
  EXPECT_CONTAINS(msg, "key 'cells[0].center_um' = [10, 2.2]");
  EXPECT_CONTAINS(msg, "bottom/top wall");
  EXPECT_CONTAINS(error_of([] { derive(channel + cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [25, 5]\nmarkers = 32")); }),
                  "outside the domain");
}

TEST(SceneCells, RejectsCoarseCellsAndBadMarkerSpacing) {
  // radius 1.25 µm = 2.5 h < 3 h.
  const std::string coarse = error_of([] { derive(channel + cell("shape = \"circle\"\nradius_um = 1.25\ncenter_um = [10, 5]\nmarkers = 16")); });
  EXPECT_CONTAINS(coarse, "resolution too coarse");
  EXPECT_CONTAINS(coarse, "cells[0].radius_um = 1.25");
  // 16 markers on a circle of radius 4 h: spacing 2·4·sin(π/16) = 1.56 h > 1 h.
  const std::string few = error_of([] { derive(channel + cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [10, 5]\nmarkers = 16")); });
  EXPECT_CONTAINS(few, "key 'cells[0].markers' = 16 is too few");
  EXPECT_CONTAINS(few, "use markers >= 25");
  EXPECT_NO_THROW(derive(channel + "[limits]\nmax_marker_spacing = 1.6\n" +
                         cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [10, 5]\nmarkers = 16")));
  // 128 markers: spacing 0.196 h < 0.3 h.
  EXPECT_CONTAINS(error_of([] { derive(channel + cell("shape = \"circle\"\nradius_um = 2.0\ncenter_um = [10, 5]\nmarkers = 128")); }),
                  "key 'cells[0].markers' = 128 is too many");
}

TEST(SceneCells, RejectsAMembraneBeyondTheStabilityLimit) {
  // E_s = 1e3 dyn/cm = 1 N/m: E_s,lat = 1 · (4.1667e-8)² / (1000 · 0.125e-18) = 13.9, and the
  // neo-Hookean stiffness dT/dλ(1) = 3 E_s gives Π_T = 41.7, far above the cosine4 limit 1.205.
  const std::string msg = error_of([] {
    derive(channel + "[membrane]\nshear_modulus_dyn_cm = 1e3\n" + circle_at_centre);
  });
  EXPECT_CONTAINS(msg, "key 'membrane.shear_modulus_dyn_cm' = 1000 dyn/cm");
  EXPECT_CONTAINS(msg, "Π_T");
  EXPECT_CONTAINS(msg, "exceeds 1.205");  // cosine4: 2.41 / safety 2 (stability.cpp), τ = 1
  EXPECT_CONTAINS(msg, "time.tau <=");
  const std::string bend = error_of([] {
    derive(channel + "[membrane]\nbending_modulus_dyn_cm = 1e-3\n" + circle_at_centre);
  });
  EXPECT_CONTAINS(bend, "key 'membrane.bending_modulus_dyn_cm'");
  EXPECT_CONTAINS(bend, "Π_B");
  const std::string area = error_of([] { derive(channel + "[membrane]\narea_modulus_Pa = 1e9\n" + circle_at_centre); });
  EXPECT_CONTAINS(area, "key 'membrane.area_modulus_Pa'");
  // The same membrane with nothing to carry it is not checked (no cells: nothing allocated).
  EXPECT_NO_THROW(derive(channel + "[membrane]\nshear_modulus_dyn_cm = 1e3\n"));
}

// limits.membrane_stability = "warn": the set-up runs, the reason is a warning `check` shows.
TEST(SceneCells, StabilityWarnRunsBeyondTheLimit) {
  const std::string text = channel + "[limits]\nmembrane_stability = \"warn\"\n[membrane]\nshear_modulus_dyn_cm = 1e3\n" +
                           circle_at_centre;
  const LatticeSetup L = derive(text);
  EXPECT_FALSE(L.membrane->stability.acceptable());
  EXPECT_CONTAINS(L.membrane->stability.warning, "key 'membrane.shear_modulus_dyn_cm' = 1000 dyn/cm");
  EXPECT_CONTAINS(L.membrane->stability.warning, "limits.membrane_stability = \"warn\"");
  const Scene s = parse_scene(text, "c.toml");
  EXPECT_CONTAINS(format_lattice_report(s, L), "warning: key 'membrane.shear_modulus_dyn_cm'");
  EXPECT_CONTAINS(error_of([] { derive(channel + "[limits]\nmembrane_stability = \"ignore\"\n"); }),
                  "key 'limits.membrane_stability' = \"ignore\" is out of range: must be one of \"reject\", \"warn\"");
}

}  // namespace
}  // namespace erythro::scene

namespace erythro::scene {
namespace {

using testing::channel_scene;
using testing::derive;
using testing::error_of;

const std::string interior_channel = channel_scene("20, 10", "0.5", "1.0", "10");
const std::string interior_cell = "\n[[cells]]\nshape = \"circle\"\nradius_um = 2.0\ncenter_um = [10, 5]\nmarkers = 32\n";

// Absent interior viscosity: no index field, the interior has the fluid's ν.
TEST(SceneInterior, AbsentMeansIndexless) {
  const LatticeSetup L = derive(interior_channel + interior_cell);
  ASSERT_TRUE(L.membrane.has_value());
  EXPECT_EQ(L.membrane->indicator, interior::Method::indexless);
  EXPECT_DOUBLE_EQ(L.membrane->interior_viscosity, L.viscosity);
}

// ν_in/ν_ex = μ_in/μ_ex (eq 27 at one density); τ = 1 → ν_ex = 1/6, ratio 5 → τ_in = 3.
TEST(SceneInterior, ConvertsViscosityAndMethod) {
  const LatticeSetup L = derive(interior_channel +
                                "[membrane]\ninterior_viscosity_cP = 5.0\ninterior_method = \"ray_casting\"\n"
                                "index_update_interval = 4\n" + interior_cell);
  ASSERT_TRUE(L.membrane.has_value());
  EXPECT_EQ(L.membrane->indicator, interior::Method::ray_casting);
  EXPECT_NEAR(L.membrane->interior_viscosity, 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(L.membrane->interior_tau, 3.0, 1e-12);
  EXPECT_EQ(L.membrane->index_update_interval, 4);
  const LatticeSetup D = derive(interior_channel + "[membrane]\ninterior_viscosity_cP = 6.0\n" + interior_cell);
  EXPECT_EQ(D.membrane->indicator, interior::Method::flood_fill);  // the thesis method by default
}

TEST(SceneInterior, RejectsBadInput) {
  EXPECT_CONTAINS(error_of([] { derive(interior_channel + "[membrane]\ninterior_method = \"band_only\"\n" + interior_cell); }),
                  "needs membrane.interior_viscosity_cP");
  EXPECT_CONTAINS(error_of([] {
                    derive(interior_channel + "[membrane]\ninterior_viscosity_cP = 6\ninterior_method = \"paint\"\n" +
                           interior_cell);
                  }),
                  "membrane.interior_method");
  EXPECT_CONTAINS(error_of([] { derive(interior_channel + "[membrane]\ninterior_viscosity_cP = 0.001\n" + interior_cell); }),
                  "interior relaxation time");
  EXPECT_CONTAINS(error_of([] {
                    derive(interior_channel + "[membrane]\ninterior_viscosity_cP = 6\nindex_update_interval = -1\n" +
                           interior_cell);
                  }),
                  "membrane.index_update_interval");
}

// k U <= 0.1 h: the largest such k, at least 1 (U in lattice units per step).
TEST(SceneInterior, SupportedIndexInterval) {
  EXPECT_EQ(supported_index_interval(0.01), 10);
  EXPECT_EQ(supported_index_interval(0.0021), 47);
  EXPECT_EQ(supported_index_interval(0.2), 1);
  EXPECT_EQ(supported_index_interval(0.0), 1);
}

// index_update_interval = 0: k from the run's max speed (a sliding top wall here); at rest, 1.
TEST(SceneInterior, DerivesTheIntervalFromTheMaxSpeed) {
  const std::string text = interior_channel + "[membrane]\ninterior_viscosity_cP = 6\nindex_update_interval = 0\n" +
                           interior_cell;
  const LatticeSetup L = derive(text, {"boundaries.top.type=\"moving_wall\"", "boundaries.top.velocity_um_s=[100, 0]"});
  ASSERT_GT(L.expected_max_speed, 0.0);
  EXPECT_EQ(L.membrane->index_update_interval, supported_index_interval(L.expected_max_speed));
  EXPECT_GT(L.membrane->index_update_interval, 1);
  const LatticeSetup rest = derive(text);
  EXPECT_EQ(rest.membrane->index_update_interval, 1);
}

}  // namespace
}  // namespace erythro::scene

namespace erythro::scene {
namespace {

using testing::channel_scene;
using testing::derive;
using testing::error_of;

const std::string pair_channel = channel_scene("20, 10", "0.25", "1.0", "10");
const std::string two_cells =
    "\n[[cells]]\nshape = \"circle\"\nradius_um = 2.0\ncenter_um = [7.7, 5]\nmarkers = 64\n"
    "[[cells]]\nshape = \"circle\"\nradius_um = 2.0\ncenter_um = [12.3, 5]\nmarkers = 64\n";

// [aggregation] → lattice Morse parameters: r0 = 0.49 µm / 0.25 µm = 1.96 h, β = 3.84 µm⁻¹ × 0.25 µm
// = 0.96 /h, default r_c = r0 + 5/β = 1.96 + 5.208 h; γ = 1.2e-5 J/m² (the former `de_star = 2`,
// read then as γ = 2 E_S with E_S = 6e-3 dyn/cm) gives a positive pair density, and the
// flat-contact gap lies below r0.
TEST(SceneAggregation, ConvertsTheSurfaceEnergy) {
  const LatticeSetup L = derive(pair_channel + "[aggregation]\nsurface_energy_J_m2 = 1.2e-5\n" + two_cells);
  ASSERT_TRUE(L.membrane && L.membrane->aggregation);
  const auto& a = *L.membrane->aggregation;
  EXPECT_NEAR(a.r0, 1.96, 1e-12);
  EXPECT_NEAR(a.beta, 0.96, 1e-12);
  EXPECT_NEAR(a.cutoff, 1.96 + 5.0 / 0.96, 1e-9);
  EXPECT_GT(a.De, 0.0);
  EXPECT_GT(L.membrane->aggregation_flat_gap, 0.0);
  EXPECT_LT(L.membrane->aggregation_flat_gap, a.r0);
  const LatticeSetup P = derive(pair_channel + "[aggregation]\npair_density_Pa = 2.0\n" + two_cells);
  EXPECT_GT(P.membrane->aggregation->De, 0.0);
}

// The literal 1.2e-5 J/m² the tests and scenes/doublet_shear.toml now give is bit for bit the γ
// of the old reading (γ = De*·E_S, E_S = membrane.shear_modulus_dyn_cm × 1e-3 N/m) at De* = 2,
// so the pair density, and every result, is unchanged by the migration.
TEST(SceneAggregation, MigratedSurfaceEnergyIsTheOldReadingsExactly) {
  const Scene s = parse_scene(pair_channel + "[aggregation]\nsurface_energy_J_m2 = 1.2e-5\n" + two_cells, "m.toml");
  const double Es_N_m = s.membrane.value_or(MembraneSpec{}).shear_modulus_dyn_cm * membrane::kDynPerCm;
  EXPECT_EQ(*s.aggregation->surface_energy_J_m2, 2.0 * Es_N_m);
  // The old code path (cell_checks.cpp before the migration): D_e = pair_density_for(De*·E_S, shape), SI.
  const AggregationSpec& a = *s.aggregation;
  const aggregation::MorseParameters shape{1.0, a.zero_force_distance_um * 1e-6, a.decay_per_um * 1e6,
                                           (a.zero_force_distance_um + 5.0 / a.decay_per_um) * 1e-6};
  const LatticeSetup L = derive_lattice(s);
  aggregation::MorsePhysical old{aggregation::pair_density_for(2.0 * Es_N_m, shape), shape.r0, shape.beta,
                                 shape.cutoff};
  const membrane::LatticeScales ms{L.scales.length_m, L.scales.time_s, L.scales.density_kg_m3};
  EXPECT_EQ(L.membrane->aggregation->De, aggregation::to_lattice(old, ms).De);
}

// De* = γ / 2.6e-8 J/m² (docs/model.md eq 4.7): De* = 5 is the thesis's 1.3e-7 J/m² (ch. IV) and
// gives the same D_e as that surface energy; it no longer involves the membrane's shear modulus.
TEST(SceneAggregation, DeStarIsTheSurfaceEnergyInUnitsOfTheThesis) {
  const LatticeSetup D = derive(pair_channel + "[aggregation]\nde_star = 5.0\n" + two_cells);
  const LatticeSetup G = derive(pair_channel + "[aggregation]\nsurface_energy_J_m2 = 1.3e-7\n" + two_cells);
  ASSERT_TRUE(D.membrane->aggregation_strength && G.membrane->aggregation_strength);
  EXPECT_DOUBLE_EQ(D.membrane->aggregation_strength->surface_energy_J_m2, 1.3e-7);
  EXPECT_DOUBLE_EQ(G.membrane->aggregation_strength->de_star, 5.0);
  EXPECT_DOUBLE_EQ(D.membrane->aggregation->De, G.membrane->aggregation->De);
  const LatticeSetup soft = derive(pair_channel + "[membrane]\nshear_modulus_dyn_cm = 4e-3\n[aggregation]\nde_star = 5.0\n" +
                                   two_cells);
  EXPECT_DOUBLE_EQ(soft.membrane->aggregation->De, D.membrane->aggregation->De);
  // Zhang et al.'s 5.2e-8 J/m² is De* = 2.
  const LatticeSetup Z = derive(pair_channel + "[aggregation]\nsurface_energy_J_m2 = 5.2e-8\n" + two_cells);
  EXPECT_DOUBLE_EQ(Z.membrane->aggregation_strength->de_star, 2.0);
}

// The strength in physical terms (docs/model.md eqs 4.6–4.8): γβ/2, and against μγ̇ only in a
// wall-driven simple shear. Channel 10 µm high, top wall at 100 µm/s, bottom still: γ̇ = 10 1/s,
// μ = 1 cP: μγ̇ = 0.01 Pa; γ = 1.3e-7 J/m², β = 3.84 µm⁻¹: γβ/2 = 0.2496 Pa.
TEST(SceneAggregation, StrengthAgainstTheViscousStressOfTheWalls) {
  const std::vector<std::string> moving_top = {"boundaries.top.type=\"moving_wall\"",
                                               "boundaries.top.velocity_um_s=[100.0, 0.0]"};
  const std::string text = pair_channel + "[aggregation]\nde_star = 5.0\n" + two_cells;
  const LatticeSetup L = derive(text, moving_top);
  const AggregationStrength& g = *L.membrane->aggregation_strength;
  const double peak = 0.5 * 1.3e-7 * 3.84e6;
  EXPECT_NEAR(g.peak_stress_Pa, peak, 1e-12 * peak);
  ASSERT_TRUE(g.shear_rate_per_s && g.adhesion_to_viscous_stress);
  EXPECT_NEAR(*g.shear_rate_per_s, 10.0, 1e-9);
  EXPECT_NEAR(*g.adhesion_to_viscous_stress, peak / (1e-3 * 10.0), 1e-9);
  // Still walls: no shear, no ratio. D_e given directly: γ = D_e |J(d*)|.
  const LatticeSetup still = derive(text);
  EXPECT_FALSE(still.membrane->aggregation_strength->shear_rate_per_s);
  EXPECT_FALSE(still.membrane->aggregation_strength->adhesion_to_viscous_stress);
  const LatticeSetup P = derive(pair_channel + "[aggregation]\npair_density_Pa = 0.1\n" + two_cells);
  const aggregation::MorseParameters shape{1.0, 0.49e-6, 3.84e6, 0.49e-6 + 5.0 / 3.84e6};
  EXPECT_NEAR(P.membrane->aggregation_strength->surface_energy_J_m2,
              0.1 * std::abs(aggregation::flat_contact(shape).integral), 1e-12 * 1.3e-7);
  // `erythro check` shows the same numbers.
  const std::string report = format_lattice_report(parse_scene(text, "a.toml", moving_top), L);
  EXPECT_CONTAINS(report, "surface energy γ");
  EXPECT_CONTAINS(report, "De* = 5 (γ / 2.6e-8 J/m²)");
  EXPECT_CONTAINS(report, "1.3e-07 J/m²");
  EXPECT_CONTAINS(report, "peak adhesion stress γβ/2");
  EXPECT_CONTAINS(report, "0.2496 Pa");
  EXPECT_CONTAINS(report, "adhesion / viscous stress");
  EXPECT_CONTAINS(report, "24.96");
  EXPECT_CONTAINS(report, "γ̇ = 10 1/s");
}

// γ = 0 (or De* = 0): no adhesion (D_e = 0), but the Morse range stays (the pair probe's contact
// and dissociation of a non-adhering control pair).
TEST(SceneAggregation, ZeroSurfaceEnergyKeepsTheRange) {
  for (const char* zero : {"surface_energy_J_m2 = 0.0\n", "de_star = 0.0\n"}) {
    const LatticeSetup L = derive(pair_channel + "[aggregation]\n" + zero + two_cells);
    ASSERT_TRUE(L.membrane && L.membrane->aggregation);
    EXPECT_EQ(L.membrane->aggregation->De, 0.0);
    EXPECT_NEAR(L.membrane->aggregation->cutoff, 1.96 + 5.0 / 0.96, 1e-9);
  }
}

TEST(SceneAggregation, RejectsBadInput) {
  EXPECT_CONTAINS(error_of([] { derive(pair_channel + "[aggregation]\nzero_force_distance_um = 0.5\n" + two_cells); }),
                  "give exactly one of aggregation.surface_energy_J_m2 (γ, J/m², >= 0), aggregation.de_star");
  EXPECT_CONTAINS(error_of([] { derive(pair_channel + "[aggregation]\nde_star = 1\npair_density_Pa = 3\n" + two_cells); }),
                  "2 given");
  EXPECT_CONTAINS(error_of([] {
                    derive(pair_channel + "[aggregation]\nde_star = 1\nsurface_energy_J_m2 = 2.6e-8\n" + two_cells);
                  }),
                  "2 given");
  EXPECT_CONTAINS(error_of([] {
                    derive(pair_channel + "[aggregation]\nde_star = 1\ncutoff_um = 0.3\n" + two_cells);
                  }),
                  "must exceed aggregation.zero_force_distance_um");
  EXPECT_CONTAINS(error_of([] { derive(pair_channel + "[aggregation]\nsurface_energy_J_m2 = -1e-7\n" + two_cells); }),
                  "key 'aggregation.surface_energy_J_m2' = -1e-07 is out of range: must be in [0, 1e+30] (J/m²)");
}

}  // namespace
}  // namespace erythro::scene
