// The index field's update runs the cells' band passes in parallel into per-cell lists and
// merges them into the field by blocks of rows; the reset and the τ rewrite run over the
// blocks too (index_field.cpp). Requirement: the same bits as one thread, where the bands
// are written one cell after the other — the field, the report, τ rewritten on the
// changed nodes, the checkpoint record and the leak message — for many cells whose bands
// and boxes overlap, a cell folded across a periodic side, cells at a wall, overlapping
// interiors and a leaking cell.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "common/state_record.hpp"
#include "geometry/shapes.hpp"
#include "interior/index_field.hpp"

using namespace erythro;
using namespace erythro::interior;

#if defined(_OPENMP)
namespace {
struct Outcome {
  std::vector<double> values, tau, dirty, marks, owners, candidates;
  std::vector<long> counts;
  std::string error;
  bool operator==(const Outcome&) const = default;
};

// Four updates of `cells` shifted by (0.37 u, −0.21 u) each, on `threads` threads.
std::vector<Outcome> run(int threads, const geometry::Domain& domain, Method method, double w,
                         std::vector<geometry::Polygon> cells) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  IndexField f(domain, IndexFieldOptions{method, w});
  std::vector<double> tau(domain.grid.size(), 0.0);
  std::vector<Outcome> out;
  for (int u = 0; u < 4; ++u) {
    Outcome o;
    try {
      const FillReport& r = f.update(cells);
      o.counts = {r.interior_nodes, r.band_nodes,        r.fallback_cells, r.fill_starts,
                  r.completion_starts, r.overlap_nodes, r.wedge_cells};
      if (u == 0)
        f.write_relaxation_times(tau, 0.5, 0.1);
      else
        f.write_changed_relaxation_times(tau, 0.5, 0.1);
      o.tau = tau;
    } catch (const FillLeakError& e) {
      o.error = e.what();
    }
    o.values.assign(f.values().begin(), f.values().end());
    StateRecord record;
    f.save_state(record, "");
    o.dirty = record.get("dirty");
    o.marks = record.get("mark");
    o.owners = record.get("owner");
    o.candidates = record.get("candidate");
    out.push_back(std::move(o));
    for (auto& p : cells) {
      for (double& x : p.x) x += 0.37;
      for (double& y : p.y) y -= 0.21;
    }
  }
  omp_set_num_threads(before);
  return out;
}

geometry::Polygon cell_at(double cx, double cy, double a, double angle, int markers = 120) {
  return geometry::transformed(geometry::biconcave(markers, a), 1.0, angle, cx, cy);
}
}  // namespace

TEST(IndexFieldThreads, ManyOverlappingCellsGiveTheSameBits) {
  // 64 × 60 nodes, periodic in x, walls in y. Biconcave cells (a = 5 h) 1–2 h apart (their
  // bands overlap), two at the walls, one across the periodic side x = 0, and a large cell
  // folded across it (its box is the whole x axis) on a narrow grid.
  std::vector<geometry::Polygon> cells;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 5; ++col)
      cells.push_back(cell_at(6.0 + 12.5 * col + 1.3 * row, 8.2 + 14.6 * row, 5.0, 0.4 * col - 0.3 * row));
  cells.push_back(cell_at(0.4, 1.1, 5.0, 0.0));    // at the bottom wall and across x = 0
  cells.push_back(cell_at(31.0, 58.9, 5.0, 0.1));  // at the top wall
  const geometry::Domain plain{Grid{64, 60}, true, false};
  const auto one = run(1, plain, Method::flood_fill, 2.0, cells);
  EXPECT_TRUE(one[0].error.empty()) << one[0].error;
  EXPECT_GT(one[0].counts[5], 0);  // overlapping bands
  EXPECT_EQ(run(2, plain, Method::flood_fill, 2.0, cells), one);
  EXPECT_EQ(run(3, plain, Method::flood_fill, 2.0, cells), one);
  EXPECT_EQ(run(2, plain, Method::ray_casting, 2.0, cells), run(1, plain, Method::ray_casting, 2.0, cells));
  EXPECT_EQ(run(2, plain, Method::flood_fill, 0.75, cells), run(1, plain, Method::flood_fill, 0.75, cells));

  const geometry::Domain narrow{Grid{28, 60}, true, false};
  const std::vector<geometry::Polygon> folded{cell_at(14.0, 15.0, 12.5, 0.05, 160), cell_at(8.0, 42.0, 5.0, 0.3),
                                              cell_at(20.5, 44.0, 5.0, -0.2), cell_at(14.0, 56.5, 3.0, 0.0)};
  const auto folded_one = run(1, narrow, Method::flood_fill, 2.0, folded);
  EXPECT_TRUE(folded_one[0].error.empty()) << folded_one[0].error;
  EXPECT_EQ(run(2, narrow, Method::flood_fill, 2.0, folded), folded_one);
}

TEST(IndexFieldThreads, MeetingFillsAndLeaksGiveTheSameBits) {
  // Two cells whose interiors overlap (their bands cut each other's interior) and, in the
  // second case, a cell with a band too thin to hold the fill (a leak, reported
  // for the same cell with the same message).
  const geometry::Domain d{Grid{64, 48}, true, true};
  const std::vector<geometry::Polygon> meeting{cell_at(20.0, 24.0, 9.0, 0.0), cell_at(30.0, 25.0, 9.0, 0.2),
                                               cell_at(52.0, 10.0, 6.0, 0.0)};
  const auto one = run(1, d, Method::flood_fill, 2.0, meeting);
  EXPECT_EQ(run(2, d, Method::flood_fill, 2.0, meeting), one);
  const auto leak_one = run(1, d, Method::flood_fill, 0.3, meeting);
  EXPECT_FALSE(leak_one[0].error.empty());
  EXPECT_EQ(run(2, d, Method::flood_fill, 0.3, meeting), leak_one);
}
#endif
