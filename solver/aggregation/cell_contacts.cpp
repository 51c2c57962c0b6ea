#include "aggregation/cell_contacts.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "aggregation/pair_sweep.hpp"
#include "aggregation/pair_terms.hpp"
#include "common/chunk_stealing.hpp"
#include "common/portable_hypot.hpp"
#include "membrane/immersed_cells.hpp"

namespace erythro::aggregation {

namespace {

constexpr std::size_t kParallelMarkers = CellContacts::kParallelMarkers;

void check_view(const MarkerView& v) {
  if (v.x.size() != v.y.size()) throw std::invalid_argument("cell contacts: x and y differ in size");
  if (v.offsets.empty() || v.offsets.front() != 0 || v.offsets.back() != v.x.size()) {
    throw std::invalid_argument("cell contacts: offsets must run from 0 to the marker count");
  }
  for (std::size_t c = 0; c + 1 < v.offsets.size(); ++c) {
    if (v.offsets[c + 1] < v.offsets[c] + 3) throw std::invalid_argument("cell contacts: a cell needs >= 3 markers");
  }
}

// The first marker with a non-finite position (called once a parallel pass has found one).
[[noreturn]] void report_non_finite(const MarkerView& v) {
  std::size_t m = 0;
  while (m < v.x.size() && std::isfinite(v.x[m]) && std::isfinite(v.y[m])) ++m;
  throw std::domain_error("cell contacts: marker " + std::to_string(m) + " has a non-finite position");
}

// The largest value (0 for none): std::max_element's value, in a loop that vectorises (a
// maximum is exact in any order).
double largest(std::span<const double> values) {
  if (values.empty()) return 0.0;
  const double* v = values.data();
  double top = v[0];
  const std::size_t n = values.size();
  // Written with the comparison, not std::max: GCC 12 builds std::max's reference into a
  // gather from the stack here, the comparison into a plain vector maximum (the same value).
#pragma omp simd reduction(max : top)
  for (std::size_t i = 1; i < n; ++i) top = v[i] > top ? v[i] : top;
  return top;
}

// The shared arithmetic of the pair-list and brute-force paths (see the header): the
// per-marker arrays, the walls and the edge part. The pair sums come from pair_terms.hpp.
struct Engine {
  const geometry::Domain& domain;
  const ContactPotential& potential;
  const MarkerView& v;
  // The per-marker arrays live in a workspace kept by the caller (no allocation per step).
  std::vector<std::size_t>& cell_of;
  std::vector<double>&edge, &ell, &S, &px, &py, &rmin;
  std::vector<double>& W;  // W(s_m) summed over the walls (eq 4.13); empty without wall repulsion
  std::size_t wall_markers = 0;
  double min_wall_gap = std::numeric_limits<double>::infinity();
  std::vector<std::size_t>& count;
  std::vector<double>& cell_closest;
  std::vector<std::size_t>& cell_pairs;
  std::vector<SweepScratch>& per_thread;
  std::atomic<bool> coincident{false};
  std::size_t beyond_wall = SIZE_MAX;  // the first marker on or beyond a wall (add_walls is serial)
  double beyond_wall_gap = 0.0;

  Engine(const geometry::Domain& d, const ContactPotential& p, const MarkerView& view, detail::ContactWorkspace& ws)
      : domain(d),
        potential(p),
        v(view),
        cell_of(ws.cell_of),
        edge(ws.edge),
        ell(ws.ell),
        S(ws.S),
        px(ws.px),
        py(ws.py),
        rmin(ws.rmin),
        W(ws.W),
        count(ws.count),
        cell_closest(ws.cell_closest),
        cell_pairs(ws.cell_pairs),
        per_thread(ws.per_thread) {
    check_view(v);
    W.clear();
    const std::size_t N = v.x.size();
    for (auto* a : {&edge, &ell, &S, &px, &py, &rmin}) a->resize(N);
    cell_of.resize(N);
    count.resize(N);
    // Per cell, over the threads (each cell its own markers: the same bits for any thread count
    // and whichever thread takes it, common/chunk_stealing.hpp):
    // the positions checked, the edge lengths, ℓ_m, and the pair sums' starting values.
    std::atomic<bool> finite{true};
    const long n_cells = static_cast<long>(v.offsets.size()) - 1;
    parallel::for_each_chunk(n_cells, N >= kParallelMarkers ? omp_get_max_threads() : 1, [&](long q) {
      const std::size_t c = static_cast<std::size_t>(q);
      const std::size_t o = v.offsets[c], e = v.offsets[c + 1];
      int cell_finite = 1;  // ints and raw pointers: a vector loop (bools and spans stayed scalar)
      const double* cx = v.x.data();
      const double* cy = v.y.data();
#pragma omp simd reduction(& : cell_finite)
      for (std::size_t k = o; k < e; ++k)
        cell_finite &= (std::isfinite(cx[k]) ? 1 : 0) & (std::isfinite(cy[k]) ? 1 : 0);
      if (cell_finite == 0) finite.store(false, std::memory_order_relaxed);
      std::fill(cell_of.begin() + o, cell_of.begin() + e, c);
      numeric::closed_polygon_lengths(&v.x[o], &v.y[o], e - o, &edge[o]);  // L_k: edge k → k+1
      for (auto* a : {&S, &px, &py}) std::fill(a->begin() + o, a->begin() + e, 0.0);
      std::fill(count.begin() + o, count.begin() + e, 0);
      std::fill(rmin.begin() + o, rmin.begin() + e, std::numeric_limits<double>::infinity());
      ell[o] = 0.5 * (edge[e - 1] + edge[o]);
      for (std::size_t k = o + 1; k < e; ++k) ell[k] = 0.5 * (edge[k - 1] + edge[k]);
    });
    if (!finite.load()) report_non_finite(v);
  }

  // Passes 1–3 of pair_terms.hpp over the n candidates of s; returns the pairs within r_c
  // (a pair at r = 0 is reported after the parallel loop: no throw inside OpenMP).
  std::size_t pair_terms(std::size_t n, PairScratch& s) {
    bool zero = false;
    const std::size_t k = evaluate_pairs(domain, potential, n, s, zero);
    if (zero) coincident.store(true, std::memory_order_relaxed);
    return k;
  }

  void store(std::size_t m, const PairSums& acc) {
    S[m] = acc.s;
    px[m] = acc.fx;
    py[m] = acc.fy;
    count[m] = acc.k;
    rmin[m] = acc.rmin;
  }

  // fn(gap, sign, axis) for each wall of a non-periodic axis within the range d of marker m,
  // in one fixed order: the x walls before the y walls, the wall at 0 (s = q, ∂s/∂q = 1)
  // before the one at L (s = L − q, ∂s/∂q = −1).
  template <class Fn>
  void for_walls_in_range(std::size_t m, double d, Fn&& fn) const {
    const double q[2] = {v.x[m], v.y[m]}, L[2] = {double(domain.grid.nx), double(domain.grid.ny)};
    const bool walls[2] = {!domain.periodic_x, !domain.periodic_y};
    for (int a = 0; a < 2; ++a) {
      if (!walls[a]) continue;
      for (const double sign : {1.0, -1.0}) {
        const double gap = sign > 0 ? q[a] : L[a] - q[a];
        if (gap < d) fn(gap, sign, a);
      }
    }
  }

  // The walls' part (eq 4.13): W_m = Σ_walls W(s) and the normal force −W'(s) ℓ_m ∂s/∂X_m,
  // for every marker within the range of a wall of a non-periodic axis (walls at 0 and n).
  void add_walls() {
    const RepulsionParameters* rep = potential.wall_repulsion();
    if (!rep || (domain.periodic_x && domain.periodic_y)) return;
    const std::size_t N = v.x.size();
    W.resize(N);
    const double d = rep->range;
    // Marker by marker in parallel (each marker its own W_m and force); the statistics are a
    // minimum, an integer sum and the first offending index: the same for any thread count.
    std::size_t near = 0, first_beyond = SIZE_MAX;
    double closest = std::numeric_limits<double>::infinity();
    const long long n_ll = static_cast<long long>(N);
#pragma omp parallel for schedule(static) if (N >= kParallelMarkers) reduction(+ : near) \
    reduction(min : closest, first_beyond)
    for (long long i = 0; i < n_ll; ++i) {
      const std::size_t m = static_cast<std::size_t>(i);
      W[m] = 0.0;
      bool touched = false;
      for_walls_in_range(m, d, [&](double gap, double sign, int axis) {
        if (!(gap > 0.0)) {
          first_beyond = std::min(first_beyond, m);
          return;
        }
        double w = 0.0, dw = 0.0;
        wall_evaluate(*rep, gap, w, dw);
        W[m] += w;
        closest = std::min(closest, gap);
        (axis == 0 ? px[m] : py[m]) -= sign * dw * ell[m];
        touched = true;
      });
      near += touched ? 1 : 0;
    }
    wall_markers = near;
    min_wall_gap = closest;
    if (first_beyond != SIZE_MAX) {  // reported with its first gap ≤ 0, in the order above
      beyond_wall = first_beyond;
      bool found = false;
      for_walls_in_range(first_beyond, d, [&](double gap, double, int) {
        if (!found && !(gap > 0.0)) {
          beyond_wall_gap = gap;
          found = true;
        }
      });
    }
  }

  void check_coincident() const {
    if (coincident.load()) throw std::domain_error("cell contacts: markers of two different cells coincide");
    if (beyond_wall != SIZE_MAX)
      throw std::domain_error("cell contacts: marker " + std::to_string(beyond_wall) + " (cell " +
                              std::to_string(cell_of[beyond_wall]) + ") is " + std::to_string(-beyond_wall_gap) +
                              " lattice spacings beyond a wall");
  }

  double energy() const {
    check_coincident();
    return energy_sum();
  }

  // E of eq 4.8 (walls: eq 4.13), one sum in marker order: its bits fix the order.
  double energy_sum() const {
    double e = 0.0;
    for (std::size_t m = 0; m < S.size(); ++m) e += ell[m] * S[m];  // E = ½ Σ ℓ_m S_m
    e *= 0.5;
    if (!W.empty()) {
      for (std::size_t m = 0; m < W.size(); ++m) e += ell[m] * W[m];  // + Σ ℓ_m W_m
    }
    return e;
  }

  // F_m = pair part + edge part (T_e = (S_e + S_{e+1})/2 along edge e), added to fx, fy; |F_m|
  // into mag. Markers o … e − 1 of one cell, the same arithmetic for each (contact_force):
  // the inner markers in a straight loop that vectorises, the two ends with the wrap.
  template <bool kWalls>
  void finish_cell(std::size_t o, std::size_t e, double* __restrict fx, double* __restrict fy,
                   double* __restrict mag) const {
    const double* x = v.x.data();
    const double* y = v.y.data();
    const double* w = kWalls ? W.data() : nullptr;
    int outside = 0;
    auto at = [&](std::size_t m, std::size_t prev, std::size_t next) {
      double gx, gy;
      contact_force<kWalls>(x, y, edge.data(), S.data(), w, px.data(), py.data(), m, prev, next, gx, gy);
      fx[m] += gx;
      fy[m] += gy;
      mag[m] = numeric::hypot_fast_flagged(gx, gy, outside);
    };
    at(o, e - 1, o + 1);
    {
      const double* __restrict L = edge.data();
      const double* __restrict s = S.data();
      const double* __restrict ax = px.data();
      const double* __restrict ay = py.data();
      const std::size_t last = e - 1;  // cells have ≥ 3 markers
#pragma omp simd reduction(| : outside)
      for (std::size_t m = o + 1; m < last; ++m) {
        double gx, gy;
        contact_force<kWalls>(x, y, L, s, w, ax, ay, m, m - 1, m + 1, gx, gy);
        fx[m] += gx;
        fy[m] += gy;
        mag[m] = numeric::hypot_fast_flagged(gx, gy, outside);
      }
    }
    at(e - 1, e - 2, o);
    if (outside != 0)  // hypot_portable's bits for every marker of the cell (portable_hypot.hpp)
      for (std::size_t m = o; m < e; ++m) {
        double gx, gy;
        const std::size_t next = m + 1 < e ? m + 1 : o, prev = m > o ? m - 1 : e - 1;
        contact_force<kWalls>(x, y, edge.data(), S.data(), w, px.data(), py.data(), m, prev, next, gx, gy);
        mag[m] = numeric::hypot_portable(gx, gy);
      }
  }

  // Marker m's force between its edges prev → m and m → next: the pair part (ax, ay) and the
  // tensions T = (∂E/∂ℓ at both ends)/2 along the two unit edge vectors (eq 4.4).
  template <bool kWalls>
  static void contact_force(const double* __restrict x, const double* __restrict y, const double* __restrict L,
                            const double* __restrict s, const double* __restrict w, const double* __restrict ax,
                            const double* __restrict ay, std::size_t m, std::size_t prev, std::size_t next,
                            double& gx, double& gy) {
    const double dm = kWalls ? s[m] + w[m] : s[m];  // ∂E/∂ℓ: S, plus W with walls
    const double dn = kWalls ? s[next] + w[next] : s[next];
    const double dp = kWalls ? s[prev] + w[prev] : s[prev];
    const double Tm = 0.5 * (dm + dn);  // edge m: m → next
    const double Tp = 0.5 * (dp + dm);  // edge prev: prev → m
    const double um_x = (x[next] - x[m]) / L[m], um_y = (y[next] - y[m]) / L[m];
    const double up_x = (x[m] - x[prev]) / L[prev], up_y = (y[m] - y[prev]) / L[prev];
    gx = ax[m] + Tm * um_x - Tp * up_x;
    gy = ay[m] + Tm * um_y - Tp * up_y;
  }

  ContactStats finish(std::span<double> fx, std::span<double> fy, std::vector<double>& magnitude) const {
    check_coincident();
    const std::size_t N = S.size();
    if (fx.size() != N || fy.size() != N) throw std::invalid_argument("cell contacts: force arrays differ in size");
    magnitude.resize(N);
    double* mag = magnitude.data();
    // Cell by cell (each cell its own markers), over the threads (common/chunk_stealing.hpp):
    // chunk 0 is the energy, one chain of additions in a fixed order (its bits), and chunk
    // 1 + c is cell c, so the thread that adds the energy takes fewer cells. Each cell keeps its
    // closest pair and its pair count; their minimum and sum are exact in any order, so any
    // thread count gives the same statistics.
    const long n_cells = static_cast<long>(v.offsets.size()) - 1;
    cell_closest.resize(static_cast<std::size_t>(n_cells));
    cell_pairs.resize(static_cast<std::size_t>(n_cells));
    double energy_total = 0.0;
    parallel::for_each_chunk(n_cells + 1, N >= kParallelMarkers ? omp_get_max_threads() : 1, [&](long chunk) {
      if (chunk == 0) {
        energy_total = energy_sum();
        return;
      }
      const std::size_t c = static_cast<std::size_t>(chunk - 1);
      const std::size_t o = v.offsets[c], e = v.offsets[c + 1];
      if (W.empty())
        finish_cell<false>(o, e, fx.data(), fy.data(), mag);
      else
        finish_cell<true>(o, e, fx.data(), fy.data(), mag);
      double closest = std::numeric_limits<double>::infinity();
      std::size_t pairs2 = 0;
      for (std::size_t m = o; m < e; ++m) {
        closest = std::min(closest, rmin[m]);
        pairs2 += count[m];
      }
      cell_closest[c] = closest;
      cell_pairs[c] = pairs2;
    });
    double closest = std::numeric_limits<double>::infinity();
    std::size_t pairs2 = 0;
    for (long q = 0; q < n_cells; ++q) {
      closest = std::min(closest, cell_closest[static_cast<std::size_t>(q)]);
      pairs2 += cell_pairs[static_cast<std::size_t>(q)];
    }
    ContactStats st;
    st.wall_markers = wall_markers;
    st.min_wall_distance = min_wall_gap;
    st.min_pair_distance = std::min(st.min_pair_distance, closest);
    st.pairs = pairs2 / 2;
    st.energy = energy_total;
    st.max_force = largest(magnitude);
    return st;
  }
};

// The pair sums of marker m over `cand`: ascending marker indices, none of m's own cell,
// containing every marker of another cell within the cut-off (the brute force: all of them).
// The passes of pair_terms.hpp with m's values in every entry, the sums in candidate order.
void pair_sums(Engine& eng, std::size_t m, std::span<const std::size_t> cand, PairScratch& s) {
  const std::size_t n = cand.size();
  s.hold(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.cx[i] = eng.v.x[cand[i]];
    s.cy[i] = eng.v.y[cand[i]];
    s.cl[i] = eng.ell[cand[i]];
  }
  std::fill_n(s.mx.begin(), n, eng.v.x[m]);
  std::fill_n(s.my.begin(), n, eng.v.y[m]);
  std::fill_n(s.ml.begin(), n, eng.ell[m]);
  const std::size_t k = eng.pair_terms(n, s);
  std::size_t q = 0;
  eng.store(m, marker_sums(s, q, k, n));
}

// Every marker against every marker of the other cells (ascending, its own cell left
// out), chunks of markers over the threads: any thread count gives the same bits.
void run_brute_force(Engine& eng) {
  const std::size_t N = eng.v.x.size();
  const long long n_ll = static_cast<long long>(N);
#pragma omp parallel if (N >= kParallelMarkers)
  {
    PairScratch s;
    std::vector<std::size_t> others;
#pragma omp for schedule(static)
    for (long long q = 0; q < n_ll; ++q) {
      const std::size_t m = static_cast<std::size_t>(q), c = eng.cell_of[m];
      others.clear();
      for (std::size_t n = 0; n < N; ++n) {
        if (n < eng.v.offsets[c] || n >= eng.v.offsets[c + 1]) others.push_back(n);
      }
      pair_sums(eng, m, others, s);
    }
  }
}

void check_periodic_cutoff(const geometry::Domain& d, double rc) {
  // Minimum image is the only image within r_c only if r_c < half the period.
  if ((d.periodic_x && !(2.0 * rc < d.grid.nx)) || (d.periodic_y && !(2.0 * rc < d.grid.ny))) {
    throw std::invalid_argument("cell contacts: the cut-off " + std::to_string(rc) +
                                " must be below half of every periodic side");
  }
}

MarkerView view_of(const membrane::ImmersedCells& cells, const std::vector<std::size_t>& offsets) {
  const std::size_t N = cells.marker_count();
  if (cells.cell_count() == 0) return {{}, {}, offsets};
  return {std::span<const double>(cells.x(0).data(), N), std::span<const double>(cells.y(0).data(), N), offsets};
}

void check_same_domain(const geometry::Domain& a, const geometry::Domain& b) {
  if (a.grid.nx != b.grid.nx || a.grid.ny != b.grid.ny || a.periodic_x != b.periodic_x || a.periodic_y != b.periodic_y) {
    throw std::invalid_argument("cell contacts: the cells live on another domain than the contact model");
  }
}

}  // namespace

CellContacts::CellContacts(const geometry::Domain& domain, const ContactLaw& law)
    : domain_(domain), potential_(law), lists_(domain, potential_.cutoff()) {
  check_periodic_cutoff(domain, potential_.cutoff());
}

// The pair sums of every marker (E is this file's Engine): the lists rebuilt when needed.
template <class E>
void CellContacts::pair_sums_all(E& eng) {
  const std::size_t N = eng.v.x.size();
  if (!lists_.valid(eng.v)) lists_.build(eng.v, eng.cell_of, threads_forces(N));
  // Over the threads from kParallelMarkers on, unless already inside the caller's region (a
  // team of one there); each pair evaluated once within a thread's cells (pair_sweep.hpp),
  // which are a slab of the domain (sweep_owners.hpp).
  const int threads = threads_forces(N) && !omp_in_parallel() ? omp_get_max_threads() : 1;
  // (A step whose forces run beside the index field, on one thread, leaves the owners as they are.)
  if (threads > 1 && !work_.owners.fits(lists_, threads, N))
    work_.owners.assign_slabs(domain_, eng.v, eng.cell_of, lists_, threads);
  const SweepArrays arrays{eng.v.x, eng.v.y, eng.ell, eng.S, eng.px, eng.py, eng.rmin, eng.count};
  if (sweep_pair_lists(domain_, potential_, lists_, work_.owners, threads, arrays, eng.per_thread))
    eng.coincident.store(true, std::memory_order_relaxed);
}

ContactStats CellContacts::add_forces(const MarkerView& markers, std::span<double> fx, std::span<double> fy) {
  Engine eng(domain_, potential_, markers, work_);
  pair_sums_all(eng);
  listed_pairs_swept_ += lists_.pairs();
  eng.add_walls();
  return eng.finish(fx, fy, magnitude_);
}

double CellContacts::energy(const MarkerView& markers) const {
  CellContacts fresh(domain_, potential_.law());  // its own pair lists: this object's are left as they are
  Engine eng(domain_, potential_, markers, fresh.work_);
  fresh.pair_sums_all(eng);
  eng.add_walls();
  return eng.energy();
}

ContactStats CellContacts::add_forces(membrane::ImmersedCells& cells) {
  check_same_domain(domain_, cells.transfer().domain());
  std::vector<std::size_t>& offsets = work_.offsets;  // reused: no allocation per step
  offsets.assign(static_cast<std::size_t>(cells.cell_count()) + 1, 0);
  for (int c = 0; c < cells.cell_count(); ++c)
    offsets[static_cast<std::size_t>(c) + 1] = cells.offset(c) + cells.size(c);
  return add_forces(view_of(cells, offsets), cells.marker_fx(), cells.marker_fy());
}

double CellContacts::energy(const membrane::ImmersedCells& cells) const {
  check_same_domain(domain_, cells.transfer().domain());
  const std::vector<std::size_t> offsets = cell_offsets(cells);
  return energy(view_of(cells, offsets));
}

std::vector<std::size_t> cell_offsets(const membrane::ImmersedCells& cells) {
  std::vector<std::size_t> o(static_cast<std::size_t>(cells.cell_count()) + 1, 0);
  for (int c = 0; c < cells.cell_count(); ++c) o[static_cast<std::size_t>(c) + 1] = cells.offset(c) + cells.size(c);
  return o;
}

double relative_contact_area(std::span<const double> mag, std::span<const std::size_t> offsets, int c, double fraction) {
  const double fmax = largest(mag);
  if (!(fmax > 0.0)) return 0.0;
  const std::size_t o = offsets[static_cast<std::size_t>(c)], e = offsets[static_cast<std::size_t>(c) + 1];
  std::size_t k = 0;
  for (std::size_t m = o; m < e; ++m) k += mag[m] > fraction * fmax ? 1 : 0;
  return double(k) / double(e - o);
}

ContactStats add_forces_brute_force(const geometry::Domain& domain, const ContactLaw& law, const MarkerView& markers,
                                    std::span<double> fx, std::span<double> fy) {
  const ContactPotential potential(law);
  check_periodic_cutoff(domain, potential.cutoff());
  detail::ContactWorkspace work;
  Engine eng(domain, potential, markers, work);
  run_brute_force(eng);
  eng.add_walls();
  std::vector<double> mag;
  return eng.finish(fx, fy, mag);
}

double energy_brute_force(const geometry::Domain& domain, const ContactLaw& law, const MarkerView& markers) {
  const ContactPotential potential(law);
  check_periodic_cutoff(domain, potential.cutoff());
  detail::ContactWorkspace work;
  Engine eng(domain, potential, markers, work);
  run_brute_force(eng);
  eng.add_walls();
  return eng.energy();
}

}  // namespace erythro::aggregation
