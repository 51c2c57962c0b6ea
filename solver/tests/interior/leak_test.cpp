// Leak detection of the index field: a fill that escapes its cell, or an interior that
// disagrees with the enclosed area, throws FillLeakError naming the cell; bad markers
// throw std::domain_error (a diverged membrane); too few markers InputError.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "geometry/shapes.hpp"
#include "interior/index_field.hpp"

using namespace erythro;
using namespace erythro::interior;
using namespace erythro::geometry;

namespace {
std::string message_of(IndexField& f, const std::vector<geometry::Polygon>& cells) {
  try {
    f.update(cells);
  } catch (const FillLeakError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Leak, BandWithGapsLeaksAndThrows) {
  // Band half-width 0.3 h < 0.5 h: a tilted membrane passes between nodes without band
  // nodes, the scan-line fill escapes into the whole periodic domain.
  IndexField f(geometry::Domain{Grid{48, 48}}, IndexFieldOptions{Method::flood_fill, 0.3});
  const auto tilted = geometry::transformed(geometry::ellipse(200, 14.0, 8.0), 1.0, 0.61, 24.0, 24.0);
  const std::string what = message_of(f, {tilted});
  EXPECT_NE(what.find("cell 0"), std::string::npos) << what;
  EXPECT_NE(what.find("leaked"), std::string::npos) << what;
}

TEST(Leak, SelfIntersectingPolygonThrows) {
  // A figure eight: shoelace area ≈ 0, but both lobes hold interior nodes. The lobes
  // turn in opposite senses, so one lobe's band signs are inverted and its fill starts
  // outside (a leak), or the interior disagrees with the area: either way, cell 1 throws.
  geometry::Polygon eight;
  for (int k = 0; k < 200; ++k) {
    const double t = 2 * std::numbers::pi * k / 200;
    eight.x.push_back(30 + 20 * std::sin(t));
    eight.y.push_back(30 + 10 * std::sin(2 * t));
  }
  for (Method m : {Method::flood_fill, Method::ray_casting}) {
    IndexField f(geometry::Domain{Grid{60, 60}}, IndexFieldOptions{m, 2.0});
    const auto ok = geometry::transformed(geometry::circle(100, 5.0), 1.0, 0.0, 8.0, 8.0);
    const std::string what = message_of(f, {ok, eight});
    EXPECT_NE(what.find("cell 1"), std::string::npos) << to_string(m) << ": " << what;
    EXPECT_TRUE(what.find("self-intersects") != std::string::npos || what.find("leaked") != std::string::npos)
        << what;
  }
}

TEST(Leak, DoublyTraversedPolygonThrows) {
  // The same circle traversed twice: shoelace area 2πr², interior πr².
  auto c = geometry::transformed(geometry::circle(100, 10.0), 1.0, 0.0, 20.0, 20.0);
  geometry::Polygon twice = c;
  twice.x.insert(twice.x.end(), c.x.begin(), c.x.end());
  twice.y.insert(twice.y.end(), c.y.begin(), c.y.end());
  IndexField f(geometry::Domain{Grid{40, 40}}, {});
  EXPECT_NE(message_of(f, {twice}).find("cell 0"), std::string::npos);
}

TEST(Leak, NonFiniteMarkerIsADomainError) {
  auto c = geometry::transformed(geometry::circle(50, 6.0), 1.0, 0.0, 10.0, 10.0);
  c.x[7] = std::numeric_limits<double>::quiet_NaN();
  IndexField f(geometry::Domain{Grid{20, 20}}, {});
  try {
    f.update(std::vector<geometry::Polygon>{c});
    FAIL() << "no throw";
  } catch (const std::domain_error& e) {  // a diverged membrane (simulation: diverged)
    EXPECT_NE(std::string(e.what()).find("marker 7"), std::string::npos) << e.what();
  }
}

TEST(Leak, ValidCellsDoNotThrowAndReportSmallMismatch) {
  // Biconcave cells with a = 13 h: the dimple is 0.207 a ≈ 2.7 h thick, all band, so each
  // interior is two lobes: the thesis start fills one, the completion pass the other.
  IndexField f(geometry::Domain{Grid{80, 80}}, {});
  std::vector<geometry::Polygon> cells;
  for (int k = 0; k < 4; ++k)
    cells.push_back(geometry::transformed(geometry::biconcave(100, 13.0), 1.0, 0.4 * k, 20.0 + 40 * (k % 2), 20.0 + 40 * (k / 2)));
  const FillReport& r = f.update(cells);
  // The curvature term (π/3 − 2/π) w² = 1.64 h² plus lattice quadrature (docs/verification-interior.md).
  EXPECT_LT(r.max_area_mismatch, 2.5);
  EXPECT_EQ(r.fill_starts, 4);
  EXPECT_EQ(r.completion_starts, 4);
  EXPECT_EQ(r.fallback_cells, 0);
}

TEST(Leak, TooFewMarkersIsAnInputError) {
  IndexField f(geometry::Domain{Grid{20, 20}}, {});
  EXPECT_THROW(f.update(std::vector<geometry::Polygon>{geometry::Polygon{{1, 2}, {1, 2}}}), InputError);
}
