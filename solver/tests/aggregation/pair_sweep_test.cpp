// Unit tests of the pair sweep's owners (aggregation/sweep_owners.hpp, pair_sweep.hpp): any
// owners give every marker's sums bit for bit, and the slabs cut across the shorter axis and share the work;
// and of the runs of partners the sweep reads (pair_lists.hpp).
#include "aggregation/pair_sweep.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "aggregation/sweep_owners.hpp"
#include "tests/aggregation/ring_grid.hpp"

using namespace erythro;
using namespace erythro::aggregation;

namespace {

const ContactLaw kLaw{MorseParameters{0.3, 2.5, 0.8, 6.0}, std::nullopt};

// Every marker's sums (S, the pair force, the closest partner, the count) under some owners.
struct Sums {
  std::vector<double> ell, S, px, py, rmin;
  std::vector<std::size_t> count;
  explicit Sums(std::size_t N)
      : ell(N), S(N, 0.0), px(N, 0.0), py(N, 0.0), rmin(N, std::numeric_limits<double>::infinity()), count(N, 0) {
    for (std::size_t m = 0; m < N; ++m) ell[m] = 0.9 + 0.01 * static_cast<double>(m % 17);
  }
};

Sums sweep(const geometry::Domain& dom, const MarkerView& v, const PairLists& lists, const SweepOwners& owners) {
  Sums s(v.x.size());
  std::vector<SweepScratch> scratch;
  const ContactPotential potential(kLaw);
  EXPECT_FALSE(sweep_pair_lists(dom, potential, lists, owners, owners.threads(),
                                SweepArrays{v.x, v.y, s.ell, s.S, s.px, s.py, s.rmin, s.count}, scratch));
  return s;
}

std::vector<std::size_t> cells_of(const MarkerView& v) {
  std::vector<std::size_t> cell(v.x.size());
  for (std::size_t c = 0; c + 1 < v.offsets.size(); ++c)
    std::fill(cell.begin() + static_cast<std::ptrdiff_t>(v.offsets[c]),
              cell.begin() + static_cast<std::ptrdiff_t>(v.offsets[c + 1]), c);
  return cell;
}

// The test rings (ring_grid.hpp) in a domain: their markers, cells and pair lists.
struct RingsIn {
  test_support::RingGrid rings{10.0, 19.5};
  MarkerView v = rings.view();
  std::vector<std::size_t> cell_of = cells_of(v);
  PairLists lists;
  explicit RingsIn(const geometry::Domain& dom) : lists(dom, ContactPotential(kLaw).cutoff()) {
    lists.build(v, cell_of, false);
  }
};

}  // namespace

TEST(SweepOwners, AnyOwnersGiveTheSameSumsBitForBit) {
  // Owners drawn at random per cell, so that a marker's partners below it interleave from
  // several threads: its sums must still be those of one thread, bit for bit. Also more
  // owners than the team has threads (they are then taken in turns).
  const geometry::Domain dom{Grid{200, 200}, true, true};
  const RingsIn r(dom);
  const MarkerView& v = r.v;
  const PairLists& lists = r.lists;
  SweepOwners one;
  one.assign_slabs(dom, v, r.cell_of, lists, 1);
  const Sums a = sweep(dom, v, lists, one);
  std::size_t pairs = 0;
  for (const std::size_t k : a.count) pairs += k;
  ASSERT_GT(pairs, 2000u);
  std::mt19937 rng(7);
  for (const int T : {2, 3, 4, 7}) {
    std::vector<unsigned> cell_owner(v.offsets.size() - 1);
    for (unsigned& o : cell_owner) o = static_cast<unsigned>(rng() % static_cast<unsigned>(T));
    SweepOwners owners;
    owners.assign(cell_owner, v, lists, T);
    ASSERT_TRUE(owners.fits(lists, T, v.x.size()));
    const Sums b = sweep(dom, v, lists, owners);
    for (std::size_t m = 0; m < v.x.size(); ++m) {
      ASSERT_EQ(a.S[m], b.S[m]) << m << " with " << T << " owners";
      ASSERT_EQ(a.px[m], b.px[m]) << m << " with " << T << " owners";
      ASSERT_EQ(a.py[m], b.py[m]) << m << " with " << T << " owners";
      ASSERT_EQ(a.rmin[m], b.rmin[m]) << m << " with " << T << " owners";
      ASSERT_EQ(a.count[m], b.count[m]) << m << " with " << T << " owners";
    }
  }
}

TEST(SweepOwners, SlabsSeparateTheFewerPairsWithEqualShares) {
  // Walls along y, periodic along x: slabs of y have one cut, slabs of x two (the rings touch
  // across the period); so two slabs of y, each of the 100 rings wholly on one side, 50 rings
  // (1 500 markers) each: alike rings, so equal work is equal cells.
  const geometry::Domain channel{Grid{200, 200}, true, false};
  const RingsIn r(channel);
  const MarkerView& v = r.v;
  SweepOwners owners;
  owners.assign_slabs(channel, v, r.cell_of, r.lists, 2);
  double top0 = -1e300, bottom1 = 1e300;
  std::size_t own0 = 0;
  for (std::size_t c = 0; c + 1 < v.offsets.size(); ++c) {
    double y = 0.0;
    for (std::size_t m = v.offsets[c]; m < v.offsets[c + 1]; ++m) y += v.y[m];
    y /= 30.0;
    const unsigned o = owners.owner()[v.offsets[c]];
    if (o == 0) top0 = std::max(top0, y), own0 += 30;
    else bottom1 = std::min(bottom1, y);
  }
  EXPECT_LT(top0, bottom1);
  EXPECT_EQ(own0, 1500u);
  // Each thread visits its own 1 500 markers and the other's that reach it: a band, not all.
  for (const int t : {0, 1}) {
    EXPECT_GE(owners.visits(t).size(), 1500u);
    EXPECT_LT(owners.visits(t).size(), 2000u);
  }
  // Periodic along both, the rings filling y but not x: slabs of x have one cut that parts
  // pairs (their cut at the period runs through empty space), slabs of y two.
  const geometry::Domain wide{Grid{400, 200}, true, true};
  const RingsIn w(wide);
  owners.assign_slabs(wide, w.v, w.cell_of, w.lists, 2);
  double right0 = -1e300, left1 = 1e300;
  for (std::size_t c = 0; c + 1 < v.offsets.size(); ++c) {
    const double x = v.x[v.offsets[c]] - 9.1;  // marker 0 of a ring sits at its centre + 9.1 along x
    if (owners.owner()[v.offsets[c]] == 0) right0 = std::max(right0, x);
    else left1 = std::min(left1, x);
  }
  EXPECT_LT(right0, left1);
}

TEST(SweepOwners, SlabsShareTheWorkNotTheCells) {
  // 70 touching rings in seven rows (each with many pairs) and 5 lone rings above them (none),
  // walls along y: slabs of y (one cut across ten columns; slabs of x would need two cuts across
  // seven rows, the rings touching across the period). Slabs of equal marker counts would give
  // thread 0 the lowest 37 rings and thread 1 the other 33 touching ones with the lone ones, so
  // thread 0 would evaluate more pairs. The slabs share the work (a cell's markers plus their
  // entries in the lists) instead: thread 0 gets fewer cells.
  const test_support::RingGrid grid{10.0, 19.5};
  std::vector<double> x, y;
  std::vector<std::size_t> off{0};
  for (int j = 0; j < 10; ++j)  // cells numbered row by row, as the slabs sort them
    for (int i = 0; i < 10; ++i) {
      if (j >= 7 && (j != 8 || i % 2 == 1)) continue;  // above the seven rows: row 8, even columns
      const auto o = static_cast<std::ptrdiff_t>(grid.off[static_cast<std::size_t>(10 * i + j)]);
      x.insert(x.end(), grid.x.begin() + o, grid.x.begin() + o + 30);
      y.insert(y.end(), grid.y.begin() + o, grid.y.begin() + o + 30);
      off.push_back(x.size());
    }
  ASSERT_EQ(off.size(), 76u);
  const MarkerView v{x, y, off};
  const std::vector<std::size_t> cell_of = cells_of(v);
  const geometry::Domain channel{Grid{190, 200}, true, false};  // gaps across the period as between rings
  PairLists lists(channel, ContactPotential(kLaw).cutoff());
  lists.build(v, cell_of, false);
  SweepOwners owners;
  owners.assign_slabs(channel, v, cell_of, lists, 2);
  std::size_t work[2] = {0, 0}, cells[2] = {0, 0}, largest = 0;
  double top0 = -1e300, bottom1 = 1e300;
  const std::span<const std::size_t> start = lists.start();
  for (std::size_t c = 0; c + 1 < off.size(); ++c) {
    const std::size_t w = (off[c + 1] - off[c]) + (start[off[c + 1]] - start[off[c]]);
    const unsigned t = owners.owner()[off[c]];
    work[t] += w;
    ++cells[t];
    largest = std::max(largest, w);
    const double yc = y[off[c]];  // marker 0 sits at the ring's centre height
    if (t == 0) top0 = std::max(top0, yc);
    else bottom1 = std::min(bottom1, yc);
  }
  EXPECT_LT(top0, bottom1);  // slabs of y
  EXPECT_LE(std::max(work[0], work[1]) - std::min(work[0], work[1]), largest);
  EXPECT_LT(cells[0], 37u);
  EXPECT_EQ(cells[0] + cells[1], 75u);
}

namespace {

// The runs the sweep reads (pair_lists.hpp): marker by marker exactly the entries above it, in
// their order, each run consecutive markers of one cell and as long as that allows.
void expect_runs_are_the_entries_above(const PairLists& lists, std::span<const std::size_t> cell_of) {
  const std::span<const std::size_t> start = lists.start(), list = lists.list(), upper = lists.upper();
  const std::span<const std::size_t> rs = lists.run_start(), first = lists.run_first(), length = lists.run_length();
  ASSERT_EQ(rs.size(), start.size());
  for (std::size_t m = 0; m + 1 < start.size(); ++m) {
    std::vector<std::size_t> from_runs;
    for (std::size_t r = rs[m]; r < rs[m + 1]; ++r) {
      ASSERT_GT(length[r], 0u);
      for (std::size_t k = 0; k < length[r]; ++k) {
        from_runs.push_back(first[r] + k);
        EXPECT_EQ(cell_of[first[r] + k], cell_of[first[r]]) << "a run across cells at marker " << m;
      }
      if (r > rs[m]) {  // the previous run could not go on
        const std::size_t next = first[r - 1] + length[r - 1];
        EXPECT_TRUE(first[r] != next || cell_of[first[r]] != cell_of[next - 1]) << "a run cut short at marker " << m;
      }
    }
    const std::vector<std::size_t> entries(list.begin() + static_cast<std::ptrdiff_t>(upper[m]),
                                           list.begin() + static_cast<std::ptrdiff_t>(start[m + 1]));
    EXPECT_EQ(from_runs, entries) << "marker " << m;
  }
}

}  // namespace

TEST(PairLists, RunsAreTheEntriesAboveEachMarkerCellByCell) {
  // The rings, periodic and walled: arcs of neighbouring rings, one run or two where an arc
  // passes a ring's marker 29 → 0.
  for (const geometry::Domain& dom :
       {geometry::Domain{Grid{200, 200}, true, true}, geometry::Domain{Grid{190, 200}, true, false}}) {
    const RingsIn r(dom);
    ASSERT_GT(r.lists.list().size(), 1000u);
    expect_runs_are_the_entries_above(r.lists, r.cell_of);
  }
  // Marker 0 (cell 0) near the last marker of cell 1 (index 5) and the first of cell 2 (index 6):
  // consecutive indices of two cells, so two runs of one partner each.
  const std::vector<double> x{10.0, 8.0, 8.0, 20.0, 20.0, 11.0, 11.0, 20.0, 20.0};
  const std::vector<double> y{10.0, 8.0, 12.0, 8.0, 12.0, 10.0, 11.0, 13.0, 16.0};
  const std::vector<std::size_t> off{0, 3, 6, 9};
  const MarkerView v{x, y, off};
  const std::vector<std::size_t> cell_of = cells_of(v);
  PairLists lists(geometry::Domain{Grid{40, 40}, false, false}, ContactPotential(kLaw).cutoff());
  lists.build(v, cell_of, false);
  expect_runs_are_the_entries_above(lists, cell_of);
  const std::span<const std::size_t> rs = lists.run_start(), first = lists.run_first();
  ASSERT_GE(rs[1] - rs[0], 2u);
  bool split = false;
  for (std::size_t r = rs[0]; r + 1 < rs[1]; ++r) split = split || (first[r] == 5 && first[r + 1] == 6);
  EXPECT_TRUE(split) << "partners 5 and 6 of two cells in one run";
}
