// Aggregation cost vs cell count (issue 6 item 8): cell lists O(N) against the
// brute-force pair loop O(N²), and the cost share of one aggregation call relative to
// one fluid step (FluidLattice::step) for the thesis doublet (201², 2 cells × 100
// markers). Speed is measured, never asserted: label `benchmark`, not CI.
//
//   aggregation_bench [--threads n] [--quick]
//
// Cells: circles R = 12 h, 100 markers (spacing 0.75 h), k × k on a jittered square
// lattice in a periodic box at 40 % area fraction, plus the 2-cell doublet. Morse as in
// the verification cases (r0 = 3.27, β = 0.576, r_c = 11.95 lattice).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <vector>

#include "aggregation/cell_contacts.hpp"
#include "configs.hpp"
#include "fluid/fluid_lattice.hpp"
#include "geometry/polygon.hpp"
#include "geometry/shapes.hpp"
#include "membrane/immersed_cells.hpp"
#include "membrane/rest_shape.hpp"

using namespace erythro;
using namespace erythro::aggregation;

namespace {

const MorseParameters kP{1e-4, 0.49 / 0.15, 3.84 * 0.15, 0.49 / 0.15 + 5.0 / (3.84 * 0.15)};

// Median of 5 timings, each repeating f until ≥ `min_s` seconds; seconds per call.
double time_call(const std::function<void()>& f, double min_s) {
  std::vector<double> t;
  for (int rep = 0; rep < 5; ++rep) {
    long n = 0;
    const auto t0 = std::chrono::steady_clock::now();
    double el = 0.0;
    do {
      f();
      ++n;
      el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    } while (el < min_s);
    t.push_back(el / double(n));
  }
  std::sort(t.begin(), t.end());
  return t[2];
}

double fit_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  const double n = double(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += std::log(x[i]) / n;
    my += std::log(y[i]) / n;
  }
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
    sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return sxy / sxx;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 1;
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--quick")) quick = true;
  }
  omp_set_num_threads(threads);
  const double min_s = quick ? 0.02 : 0.2;
  std::printf("# aggregation scaling, %d thread(s); circles R = 12, 100 markers, 40 %% area fraction\n", threads);
  // pair_lists_s: a call that reuses the pair lists (markers moved less than skin/2, the
  // common step); with_build_s: a call that builds them first (a new CellContacts).
  std::printf("%8s %9s %8s %10s %14s %14s %14s %12s %12s\n", "cells", "markers", "box", "pairs", "pair_lists_s",
              "with_build_s", "brute_force_s", "ns/marker", "build_ns/mk");
  std::vector<double> nm, tc;
  const int ks[] = {1, 2, 3, 4, 6, 8, 11, 14, 17};
  for (int k : ks) {
    vv::MarkerConfig c = vv::lattice_cells(k == 1 ? 2 : k, 100, 12.0, 0.40, 42);
    if (k == 1) {  // the doublet: the first two cells of a 2 × 2 lattice
      c.x.resize(200);
      c.y.resize(200);
      c.offsets.resize(3);
    }
    CellContacts agg(c.domain, kP);
    std::vector<double> fx(c.markers(), 0.0), fy(c.markers(), 0.0);
    ContactStats st;
    const double t = time_call([&] { st = agg.add_forces(c.view(), fx, fy); }, min_s);
    const double tw = time_call([&] {
      CellContacts fresh(c.domain, kP);
      fresh.add_forces(c.view(), fx, fy);
    }, min_s);
    double tb = NAN;
    if (c.markers() <= 4000) tb = time_call([&] { add_forces_brute_force(c.domain, ContactLaw{kP, std::nullopt}, c.view(), fx, fy); }, min_s);
    std::printf("%8zu %9zu %8d %10zu %14.6e %14.6e %14.6e %12.1f %12.1f\n", c.offsets.size() - 1, c.markers(),
                c.domain.grid.nx, st.pairs, t, tw, tb, 1e9 * t / double(c.markers()), 1e9 * tw / double(c.markers()));
    nm.push_back(double(c.markers()));
    tc.push_back(t);
  }
  std::printf("# fitted slope d log t / d log N (cell lists): all %.3f; N >= 1600 markers: %.3f\n", fit_slope(nm, tc),
              fit_slope(std::vector<double>(nm.begin() + 3, nm.end()), std::vector<double>(tc.begin() + 3, tc.end())));

  // Cost share for the thesis doublet: 201², two Evans–Fung cells a = 3.91/0.15 = 26.07 h,
  // 100 markers each, 1 h apart along x at the centre.
  {
    fluid::FluidLattice lat(Grid{201, 201}, fluid::CollisionConfig{fluid::CollisionModel::bgk, 1.0, 3.0 / 16.0},
                            fluid::BoundaryConfig{});
    membrane::ImmersedCells cells(ib::KernelType::cosine4, lat);
    const double a = 3.91 / 0.15;
    const geometry::Polygon s = geometry::biconcave(100, a);
    const membrane::RestShape rest = membrane::RestShape::from_polygon(s);
    const membrane::MembraneModel model{{membrane::TensionLawType::neo_hookean, 0.01}, 0.1, 0.01};
    // Rotated upright, rims ~0.62a thick; centres 0.62a + r0 apart.
    const double d = 0.62 * a + kP.r0;
    cells.add_cell(geometry::transformed(s, 1.0, 0.5 * 3.141592653589793, 100.5 - 0.5 * d, 100.5), rest, model);
    cells.add_cell(geometry::transformed(s, 1.0, 0.5 * 3.141592653589793, 100.5 + 0.5 * d, 100.5), rest, model);
    CellContacts agg(cells.transfer().domain(), kP);
    ContactStats st;
    cells.compute_forces();
    const double t_fluid = time_call([&] { lat.step(); }, min_s);
    const double t_agg = time_call([&] { st = agg.add_forces(cells); }, min_s);
    const double t_mem = time_call([&] { cells.compute_forces(); }, min_s);
    const double t_ib = time_call([&] { cells.advance(lat); }, min_s);
    std::printf("# thesis doublet 201^2, 2 x 100 markers, %zu pairs in range\n", st.pairs);
    std::printf("fluid_step_s %.6e  aggregation_s %.6e  membrane_forces_s %.6e  ib_cycle_s %.6e\n", t_fluid, t_agg, t_mem,
                t_ib);
    std::printf("aggregation / fluid step = %.4f ; aggregation / (IB cycle) = %.4f\n", t_agg / t_fluid, t_agg / t_ib);
  }
  return 0;
}
