// Case verification.interior_fill_agreement (issue 5 item 4).
//
// Requirement: the thesis's scan-line flood fill (docs/model.md §5 step 3) marks exactly the
// nodes that even–odd ray casting marks as inside, node for node away from the band, on
// a suite of configurations (circle, ellipse, biconcave, random Fourier-mode stars, folded
// horseshoes, cells across periodic sides, small cells, pairs closer than the band width,
// cells at walls); and the band values are eq 26 of the true signed distance.
// Reference: the even–odd rule (a node is inside iff a ray from it crosses the polygon an
// odd number of times) evaluated independently per node (geometry::signed_distance, which
// loops over every edge of every periodic image), and eq 26 H(d) with the minimum over
// cells where bands overlap (the rule of index_field.hpp).
// Why exact: away from the band the fill and the rule are both set-valued and the band is
// watertight (|d| is 1-Lipschitz, so a 4-connected path from d < −2h to d > 2h meets a node
// with |d| < 2h): any mismatch is a bug, not a discretisation error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

#include "common/case_support.hpp"
#include "geometry/grid_polygon.hpp"
#include "interior/index_field.hpp"
#include "test_shapes.hpp"

using namespace erythro;
using namespace erythro::interior;
using namespace erythro::geometry;

namespace {
constexpr double kW = 2.0;  // band half-width, lattice units (eq 26)

struct Reference {
  std::vector<std::uint8_t> inside;  // even–odd inside any cell, any periodic image
  std::vector<std::uint8_t> band;    // |d| < w for some cell
  std::vector<double> band_value;    // min over cells of H(d)
};

// Independent per-node reference: signed distance to each cell over its periodic images.
Reference reference(const vv::CellScene& s) {
  const Grid& g = s.domain.grid;
  Reference r{std::vector<std::uint8_t>(g.size(), 0), std::vector<std::uint8_t>(g.size(), 0),
              std::vector<double>(g.size(), 1.0)};
  for (const auto& p : s.cells) {
    const auto [x0, x1] = std::minmax_element(p.x.begin(), p.x.end());
    const auto [y0, y1] = std::minmax_element(p.y.begin(), p.y.end());
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        for (int ky = -2; ky <= 2; ++ky)
          for (int kx = -2; kx <= 2; ++kx) {
            if ((kx && !s.domain.periodic_x) || (ky && !s.domain.periodic_y)) continue;
            const double px = i + 0.5 + kx * g.nx, py = j + 0.5 + ky * g.ny;
            if (px < *x0 - kW || px > *x1 + kW || py < *y0 - kW || py > *y1 + kW) continue;
            const double d = signed_distance(p, px, py);
            const std::size_t k = g.index(i, j);
            if (d < 0) r.inside[k] = 1;
            if (std::abs(d) < kW) {
              r.band[k] = 1;
              r.band_value[k] = std::min(r.band_value[k], smoothed_heaviside(d, kW));
            }
          }
  }
  return r;
}
}  // namespace

TEST(InteriorFillAgreement, FloodFillEqualsRayCasting) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.interior_fill_agreement", "interior");
  record.set_requirement(
      "The scan-line flood fill of the thesis (docs/model.md section 5) sets I = 0 on exactly the nodes that the "
      "even-odd ray-casting rule finds inside a cell, node for node away from the band, and I = H(d) of eq 26 "
      "(minimum over cells) in the band, on circles, ellipses, biconcave cells, random Fourier-mode stars, folded "
      "horseshoes, cells across periodic sides, small cells, pairs closer than the band width and cells at walls.");
  record.set_reference(
      "Even-odd rule per node, independently (geometry::signed_distance over all edges and periodic images); "
      "eq 26 H(d) = (1 + d/2h + sin(pi d/2h)/pi)/2, thesis section II.4; overlap rule: minimum I (index_field.hpp).");
  record.set_parameter("band_half_width_h", kW);
  record.set_parameter("suite", std::string("smooth shapes; 6 random-star scenes (seeds 1-6, 4 cells, 2-6 modes); 4 "
                                            "horseshoe scenes (seeds 11-14); periodic crossings; 24 small cells; "
                                            "close pairs gap 0.3-3.45 h; near walls"));
  long mismatch_fill_ray = 0, mismatch_fill_rule = 0, compared = 0, fallbacks = 0, overlaps = 0, total_cells = 0;
  long wedge_cells = 0;
  double band_dev = 0.0, worst_area = 0.0;
  for (const vv::CellScene& s : vv::agreement_suite()) {
    vv::Stopwatch clock;
    IndexField fill(s.domain, {Method::flood_fill, kW}), ray(s.domain, {Method::ray_casting, kW});
    const FillReport rf = fill.update(s.cells);
    ray.update(s.cells);
    const Reference ref = reference(s);
    long m_ray = 0, m_rule = 0, away = 0;
    double dev = 0.0;
    for (std::size_t k = 0; k < s.domain.grid.size(); ++k) {
      const double I = fill.values()[k];
      m_ray += (I == 0.0) != (ray.values()[k] == 0.0);
      if (ref.band[k]) {
        dev = std::max(dev, std::abs(I - (ref.inside[k] && I == 0.0 ? 0.0 : ref.band_value[k])));
      } else {
        ++away;
        m_rule += (I == 0.0) != (ref.inside[k] != 0);
        m_rule += (I != 0.0 && I != 1.0);  // away from every band I is 0 or 1
      }
    }
    std::cout << s.name << ": cells " << s.cells.size() << " interior " << rf.interior_nodes << " band "
              << rf.band_nodes << " starts " << rf.fill_starts << " completion " << rf.completion_starts << " fallback "
              << rf.fallback_cells << " wedge " << rf.wedge_cells << " overlap " << rf.overlap_nodes << " | mismatch fill-ray " << m_ray
              << " fill-rule " << m_rule << " band dev " << dev << " area " << rf.max_area_mismatch << "\n";
    record.add_run({{"scene", s.name}, {"cells", double(s.cells.size())}, {"nx", double(s.domain.grid.nx)},
                    {"ny", double(s.domain.grid.ny)}, {"interior_nodes", double(rf.interior_nodes)},
                    {"band_nodes", double(rf.band_nodes)}, {"fill_starts", double(rf.fill_starts)},
                    {"completion_starts", double(rf.completion_starts)}, {"fallback_cells", double(rf.fallback_cells)}, {"wedge_cells", double(rf.wedge_cells)},
                    {"overlap_nodes", double(rf.overlap_nodes)}, {"nodes_away_from_band", double(away)},
                    {"mismatch_fill_vs_ray_casting", double(m_ray)}, {"mismatch_fill_vs_even_odd", double(m_rule)},
                    {"max_band_deviation", dev}, {"max_area_mismatch", rf.max_area_mismatch},
                    {"wall_time_s", clock.seconds()}});
    mismatch_fill_ray += m_ray;
    mismatch_fill_rule += m_rule;
    compared += away;
    band_dev = std::max(band_dev, dev);
    fallbacks += rf.fallback_cells;
    overlaps += rf.overlap_nodes;
    total_cells += rf.cells;
    wedge_cells += rf.wedge_cells;
    worst_area = std::max(worst_area, rf.max_area_mismatch);
  }
  EXPECT_TRUE(record.add_metric({"mismatch flood fill vs ray casting method", "nodes where I = 0 differs between "
                                 "the flood_fill and ray_casting methods, all scenes, all nodes", "nodes",
                                 double(mismatch_fill_ray), 0.0, 0.0, io::Comparison::at_most,
                                 "both methods share the band and mark a set of nodes: agreement is exact or a bug"}));
  EXPECT_TRUE(record.add_metric({"mismatch flood fill vs even-odd rule", "nodes away from every band where the fill's "
                                 "I = 0 differs from the independent even-odd inside test (or I is not 0/1)", "nodes",
                                 double(mismatch_fill_rule), 0.0, 0.0, io::Comparison::at_most,
                                 "set-valued and the band is watertight: exact agreement required"}));
  EXPECT_TRUE(record.add_metric({"band deviation from eq 26", "max |I - min_c H(d_c)| over band nodes, d from the "
                                 "independent signed distance", "", band_dev, 1e-12, 0.0, io::Comparison::at_most,
                                 "same formula, distances from the same segments: only round-off (1e-12) allowed"}));
  EXPECT_TRUE(record.add_metric({"nodes compared", "nodes away from the band over the suite (the test is not empty)",
                                 "nodes", double(compared), 50000.0, 0.0, io::Comparison::at_least,
                                 "the suite covers about 1.4e5 nodes; fewer would mean scenes were skipped"}));
  record.set_parameter("cells_total", double(total_cells));
  record.set_parameter("fallback_cells_total", double(fallbacks));
  record.set_parameter("wedge_cells_total", double(wedge_cells));
  // Both band-pass paths (per-edge wedges and whole capsules) must be exercised.
  EXPECT_TRUE(record.add_metric({"cells on each band-pass path", "min(cells using wedges, cells using capsules)",
                                 "cells", double(std::min(wedge_cells, total_cells - wedge_cells)), 5.0, 0.0,
                                 io::Comparison::at_least,
                                 "the agreement must cover both paths of the band pass; 5 cells each at least"}));
  record.set_parameter("overlap_nodes_total", double(overlaps));
  record.set_parameter("max_area_mismatch_h2", worst_area);
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
