// The contact stage allocates nothing once its buffers have grown (issue 18: the pair lists
// "built without allocation per step"): every C++ allocation of this test program is counted
// (its own operator new), and a rebuild of the pair lists, or a whole call of the contact
// forces with a rebuild in it, on two threads, must add none. Its own executable, so that the
// counting new touches no other test.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>
#include <optional>
#include <vector>

#include "aggregation/cell_contacts.hpp"
#include "aggregation/pair_lists.hpp"
#include "tests/aggregation/ring_grid.hpp"

namespace {
std::atomic<long> g_allocations{0};
}

// The replacement pair below: new by malloc, delete by free. GCC, inlining the delete where a
// new of this file allocated, takes free() for a mismatched release (-Wmismatched-new-delete);
// here it is the matching one.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return ::operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using namespace erythro;
using namespace erythro::aggregation;

namespace {

const ContactLaw kLaw{MorseParameters{0.3, 2.5, 0.8, 6.0}, std::nullopt};

// The rings of ring_grid.hpp (3 000 markers) and the same rings with every marker moved by a
// few tenths of a lattice unit, enough that the lists change (other pairs, other lengths).
struct TwoPlacings {
  test_support::RingGrid a{10.0, 19.5};
  std::vector<double> bx = a.x, by = a.y;
  std::vector<std::size_t> cell_of;
  TwoPlacings() {
    for (std::size_t m = 0; m < bx.size(); ++m) {
      bx[m] += 0.3 * std::sin(0.7 * static_cast<double>(m));
      by[m] += 0.3 * std::cos(1.3 * static_cast<double>(m));
    }
    for (std::size_t c = 0; c + 1 < a.off.size(); ++c)
      for (std::size_t m = a.off[c]; m < a.off[c + 1]; ++m) cell_of.push_back(c);
  }
  MarkerView first() const { return a.view(); }
  MarkerView second() const { return {bx, by, a.off}; }
};

}  // namespace

TEST(Allocation, PairListRebuildsAllocateNothingOnceGrown) {
  omp_set_num_threads(2);
  const geometry::Domain dom{Grid{200, 200}, true, true};
  const TwoPlacings p;
  PairLists lists(dom, ContactPotential(kLaw).cutoff());
  lists.build(p.first(), p.cell_of, true);  // the buffers grow to both placings' sizes
  lists.build(p.second(), p.cell_of, true);
  const std::size_t pairs_second = lists.pairs();
  const long before = g_allocations.load();
  lists.build(p.first(), p.cell_of, true);
  lists.build(p.second(), p.cell_of, true);
  const long added = g_allocations.load() - before;
  EXPECT_EQ(added, 0) << "allocations in two rebuilds of the pair lists";
  EXPECT_EQ(lists.pairs(), pairs_second);
  EXPECT_GT(lists.pairs(), 1000u);
}

TEST(Allocation, ContactForcesWithARebuildAllocateNothingOnceGrown) {
  omp_set_num_threads(2);
  const geometry::Domain dom{Grid{200, 200}, true, true};
  const TwoPlacings p;
  CellContacts contacts(dom, kLaw);
  std::vector<double> fx(p.bx.size(), 0.0), fy(p.bx.size(), 0.0);
  contacts.add_forces(p.first(), fx, fy);
  contacts.add_forces(p.second(), fx, fy);
  const std::size_t builds = contacts.pair_list_builds();
  const long before = g_allocations.load();
  contacts.add_forces(p.first(), fx, fy);  // each call rebuilds: the markers moved by more than half the skin
  contacts.add_forces(p.second(), fx, fy);
  const long added = g_allocations.load() - before;
  EXPECT_EQ(added, 0) << "allocations in two calls of the contact forces";
  EXPECT_EQ(contacts.pair_list_builds(), builds + 2);
}
