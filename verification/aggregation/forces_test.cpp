// Case verification.aggregation_forces (issue 6 item 3).
//
// Requirement: the Morse aggregation forces are the exact negative gradient of the
// discrete energy (aggregation/cell_contacts.hpp), their pair structure makes the
// total force and torque vanish to round-off, and the cell-list search returns
// bit-for-bit the brute-force result.
// Reference: F_m = −∂E/∂X_m; central differences of E with step ε have error
// ε²/6·|∂³E| (truncation, ~1e-10·|F| at ε = 1e-5 with β ~ 0.6) plus u·|E_terms|/ε (round-off,
// u = 1.1e-16), so ≤ 1e-7·max|F| leaves margin but fails for any missing term (the ∂ℓ/∂X
// edge terms are a few % of the force). Newton's third law per pair:
// Σ F and Σ X × F vanish up to the rounding of the sums, ~N·u relative.
// Set-up: Evans–Fung and circular cells, a = 6–10, jittered markers, periodic boxes with
// cells stored unwrapped across the sides, wall-bounded boxes, up to 100 cells.
#include <gtest/gtest.h>

#include <cmath>
#include <omp.h>
#include <random>

#include "aggregation/cell_contacts.hpp"
#include "common/case_support.hpp"
#include "configs.hpp"
#include "geometry/polygon.hpp"
#include "geometry/shapes.hpp"

using namespace erythro;
using namespace erythro::aggregation;

namespace {

// Lattice parameters of the thesis doublet (h = 0.15 µm, docs/parameters.md rows Morse r0,
// Morse β): r0 = 0.49/0.15 = 3.27, β = 3.84·0.15 = 0.576, cut-off r0 + 5/β ≈ 11.95 h.
const MorseParameters kP{1e-3, 0.49 / 0.15, 3.84 * 0.15, 0.49 / 0.15 + 5.0 / (3.84 * 0.15)};

// Two biconcave cells face to face (gap ≈ r0), jittered, the pair straddling the periodic
// x side: cell 1 is stored at x + L (unwrapped), so every separation needs the minimum image.
vv::MarkerConfig doublet(bool wrap, std::uint64_t seed) {
  vv::MarkerConfig c;
  const int L = 64;
  c.domain = geometry::Domain{Grid{L, L}, true, true};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const double a = 10.0;
  const geometry::Polygon s = geometry::biconcave(100, a);  // long axis along x
  // Rotate by π/2: long axes vertical, the flat faces (thickness ≈ 0.2a… 0.7a) face each other.
  const double half = 0.5 * 0.7 * a;
  for (int k = 0; k < 2; ++k) {
    const double cx = (wrap ? 2.0 : 32.0) + (k == 0 ? -1 : 1) * (half + 0.5 * kP.r0);
    geometry::Polygon p = geometry::transformed(s, 1.0, 0.5 * 3.141592653589793 + 0.05 * u(rng), cx, 30.0 + u(rng));
    for (std::size_t i = 0; i < p.size(); ++i) {
      p.x[i] += 0.3 * u(rng);
      p.y[i] += 0.3 * u(rng);
      if (wrap && k == 0) p.x[i] += L;  // cell 0 near x = L, stored unwrapped beyond it
    }
    vv::add_cell(c, p.x, p.y);
  }
  return c;
}

struct FdResult {
  double max_error = 0.0;  // max |F_fd − F| / max |F|
  double max_force = 0.0;
};

// Central differences of E at every `stride`-th marker (both axes) against add_forces.
FdResult finite_difference_check(vv::MarkerConfig c, const MorseParameters& p, double eps, std::size_t stride = 1) {
  CellContacts agg(c.domain, p);
  std::vector<double> fx(c.markers(), 0.0), fy(c.markers(), 0.0);
  agg.add_forces(c.view(), fx, fy);
  FdResult r;
  for (std::size_t m = 0; m < c.markers(); ++m) r.max_force = std::max(r.max_force, std::hypot(fx[m], fy[m]));
  for (std::size_t m = 0; m < c.markers(); m += stride) {
    for (int axis = 0; axis < 2; ++axis) {
      std::vector<double>& q = axis == 0 ? c.x : c.y;
      const double q0 = q[m];
      q[m] = q0 + eps;
      const double ep = agg.energy(c.view());
      q[m] = q0 - eps;
      const double em = agg.energy(c.view());
      q[m] = q0;
      const double fd = -(ep - em) / (2.0 * eps);
      const double f = axis == 0 ? fx[m] : fy[m];
      r.max_error = std::max(r.max_error, std::abs(fd - f));
    }
  }
  r.max_error /= r.max_force;
  return r;
}

}  // namespace

TEST(AggregationForces, All) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.aggregation_forces", "aggregation");
  record.set_requirement(
      "Morse aggregation forces equal -grad E of the discrete pair energy (central differences, relative error "
      "<= 1e-7), total force and torque of the pair forces vanish to round-off (<= 1e-13 relative), and the cell-list "
      "search gives bit-for-bit the brute-force forces and energy on random configurations.");
  record.set_reference(
      "E = sum Phi_s(r_mn) l_m l_n over markers of different cells (docs/model.md sec. 4, force-shifted cut-off); "
      "F = -dE/dX incl. the dl/dX edge terms; Newton's third law per pair.");
  record.set_parameter("morse", std::string("De = 1e-3, r0 = 3.267, beta = 0.576, cutoff = r0 + 5/beta = 11.95 (lattice)"));
  record.set_parameter("fd_step", 1e-5);

  // 1. Finite differences: a face-to-face doublet (in the box and wrapped across x).
  for (bool wrap : {false, true}) {
    const auto c = doublet(wrap, 7);
    vv::Stopwatch sw;
    const FdResult r = finite_difference_check(c, kP, 1e-5);
    const std::string name = wrap ? "fd_doublet_wrapped" : "fd_doublet";
    record.add_run({{"check", name}, {"markers", double(c.markers())}, {"error", r.max_error},
                    {"wall_time_s", sw.seconds()}});
    EXPECT_TRUE(record.add_metric({name, "max |F_fd - F| / max |F| over all markers and axes", "", r.max_error, 1e-7,
                                   0.0, io::Comparison::at_most,
                                   "central FD at eps = 1e-5: truncation eps^2/6 |E'''| ~ 1e-10, round-off u E/eps ~ "
                                   "1e-10 relative; a missing term is O(1)"}))
        << r.max_error;
  }
  // The same on 30 random cells in a periodic box, a third stored unwrapped (every 23rd marker).
  {
    const auto c = vv::random_cells(30, 64, 96, 80, true, 12);
    vv::Stopwatch sw;
    const FdResult r = finite_difference_check(c, kP, 1e-5, 23);
    record.add_run({{"check", std::string("fd_periodic_30")}, {"markers", double(c.markers())}, {"error", r.max_error},
                    {"wall_time_s", sw.seconds()}});
    EXPECT_TRUE(record.add_metric({"fd_periodic_30", "max |F_fd - F| / max |F|, 30 random cells, every 23rd marker", "",
                                   r.max_error, 1e-7, 0.0, io::Comparison::at_most,
                                   "as fd_doublet; overlapping random cells give larger, rougher forces"}))
        << r.max_error;
  }

  // 2. Total force and torque of a doublet (not wrapped: positions are the true separations).
  {
    const auto c = doublet(false, 11);
    CellContacts agg(c.domain, kP);
    std::vector<double> fx(c.markers(), 0.0), fy(c.markers(), 0.0);
    const ContactStats st = agg.add_forces(c.view(), fx, fy);
    double sx = 0, sy = 0, tq = 0, fabs = 0, tabs = 0;
    for (std::size_t m = 0; m < c.markers(); ++m) {
      sx += fx[m];
      sy += fy[m];
      tq += c.x[m] * fy[m] - c.y[m] * fx[m];
      fabs += std::hypot(fx[m], fy[m]);
      tabs += std::hypot(c.x[m], c.y[m]) * std::hypot(fx[m], fy[m]);
    }
    const double frel = std::hypot(sx, sy) / fabs, trel = std::abs(tq) / tabs;
    // Net force on each cell is nonzero (attraction): the sum over the pair is what cancels.
    double c0x = 0;
    for (std::size_t m = c.offsets[0]; m < c.offsets[1]; ++m) c0x += fx[m];
    record.add_run({{"check", std::string("doublet_sums")}, {"markers", double(c.markers())}, {"error", frel},
                    {"wall_time_s", 0.0}});
    record.set_parameter("doublet_pairs", double(st.pairs));
    record.set_parameter("doublet_cell0_net_fx_over_sum_abs", c0x / fabs);
    EXPECT_TRUE(record.add_metric({"total_force", "|sum F| / sum |F| on the doublet", "", frel, 1e-13, 0.0,
                                   io::Comparison::at_most,
                                   "pair forces are bitwise opposite; only the summation rounds (~N u = 2e-14)"}))
        << frel;
    EXPECT_TRUE(record.add_metric({"total_torque", "|sum X x F| / sum |X||F| on the doublet", "", trel, 1e-13, 0.0,
                                   io::Comparison::at_most, "central pair forces; summation round-off ~N u"}))
        << trel;
    EXPECT_GT(std::abs(c0x / fabs), 1e-3);  // the test is not vacuous: each cell feels a net pull
  }

  // 3. Cell lists vs brute force, bit for bit, on random configurations.
  struct Case {
    const char* name;
    int cells, markers, nx, ny;
    bool periodic;
    std::uint64_t seed;
  };
  const Case cases[] = {{"periodic_3", 3, 100, 40, 40, true, 1},     {"periodic_30", 30, 64, 96, 80, true, 2},
                        {"periodic_100", 100, 64, 200, 160, true, 3}, {"walls_40", 40, 64, 120, 100, false, 4},
                        {"small_box_2bins", 6, 48, 25, 30, true, 5}};
  for (const Case& k : cases) {
    const auto c = vv::random_cells(k.cells, k.markers, k.nx, k.ny, k.periodic, k.seed);
    CellContacts agg(c.domain, kP);
    std::vector<double> fx(c.markers(), 0.0), fy(c.markers(), 0.0), bx(c.markers(), 0.0), by(c.markers(), 0.0);
    // The cell lists on two threads whatever OMP_NUM_THREADS says (the comparison with one thread
    // below must not become one thread against one).
    const int threads = omp_get_max_threads();
    omp_set_num_threads(2);
    vv::Stopwatch sw;
    const ContactStats a = agg.add_forces(c.view(), fx, fy);
    const double t_cl = sw.seconds();
    omp_set_num_threads(threads);
    vv::Stopwatch sb;
    const ContactStats b = add_forces_brute_force(c.domain, ContactLaw{kP, std::nullopt}, c.view(), bx, by);
    const double t_bf = sb.seconds();
    // Same with one thread: deterministic for any thread count.
    omp_set_num_threads(1);
    std::vector<double> sx(c.markers(), 0.0), sy(c.markers(), 0.0);
    agg.add_forces(c.view(), sx, sy);
    omp_set_num_threads(threads);
    double diff = 0.0, diff1 = 0.0;
    for (std::size_t m = 0; m < c.markers(); ++m) {
      diff = std::max({diff, std::abs(fx[m] - bx[m]), std::abs(fy[m] - by[m])});
      diff1 = std::max({diff1, std::abs(fx[m] - sx[m]), std::abs(fy[m] - sy[m])});
    }
    const double ediff = std::abs(a.energy - b.energy);
    record.add_run({{"check", std::string(k.name)}, {"markers", double(c.markers())}, {"error", diff + ediff + diff1},
                    {"wall_time_s", t_cl + t_bf}});
    record.add_run({{"check", std::string(k.name) + "_pairs"}, {"markers", double(a.pairs)},
                    {"error", double(a.pairs) - double(b.pairs)}, {"wall_time_s", t_bf}});
    EXPECT_TRUE(record.add_metric({std::string("bitwise_") + k.name,
                                   "max |F_cells - F_brute| + |E_cells - E_brute| + max |F_2threads - F_1thread|", "",
                                   diff + ediff + diff1, 0.0, 0.0, io::Comparison::at_most,
                                   "same pair set summed in the same (ascending) order: identical bits"}))
        << k.name;
    EXPECT_EQ(a.pairs, b.pairs) << k.name;
    EXPECT_GT(a.pairs, 0u) << k.name;  // not vacuous
  }
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
