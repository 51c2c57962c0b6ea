#include "aggregation/cell_contacts.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "membrane/immersed_cells.hpp"

namespace erythro::aggregation {

namespace {

constexpr std::size_t kParallelMarkers = CellContacts::kParallelMarkers;

// Minimum-image difference on a periodic axis of length L, inv = 1/L. Symmetric:
// image(−d) = −image(d) bit for bit (−d·inv = −(d·inv) exactly, and round-to-nearest-even
// of nearbyint is odd-symmetric).
inline double image(double d, bool periodic, double L, double inv) {
  return periodic ? d - L * std::nearbyint(d * inv) : d;
}

void check_view(const MarkerView& v) {
  if (v.x.size() != v.y.size()) throw std::invalid_argument("cell contacts: x and y differ in size");
  if (v.offsets.empty() || v.offsets.front() != 0 || v.offsets.back() != v.x.size()) {
    throw std::invalid_argument("cell contacts: offsets must run from 0 to the marker count");
  }
  for (std::size_t c = 0; c + 1 < v.offsets.size(); ++c) {
    if (v.offsets[c + 1] < v.offsets[c] + 3) throw std::invalid_argument("cell contacts: a cell needs >= 3 markers");
  }
  for (std::size_t m = 0; m < v.x.size(); ++m) {
    if (!std::isfinite(v.x[m]) || !std::isfinite(v.y[m])) {
      throw std::domain_error("cell contacts: marker " + std::to_string(m) + " has a non-finite position");
    }
  }
}

// The shared arithmetic of the cell-list and brute-force paths (see the header): the
// per-marker arrays and the walls. The pair sums are sums_over_candidates (below).
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
  std::vector<detail::PairScratch>& per_thread;
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
        per_thread(ws.per_thread) {
    check_view(v);
    W.clear();
    const std::size_t N = v.x.size();
    cell_of.resize(N);
    edge.resize(N);
    ell.resize(N);
    const long n_cells = static_cast<long>(v.offsets.size()) - 1;  // each cell its own markers: the same bits
#pragma omp parallel for schedule(static) if (N >= kParallelMarkers)
    for (long q = 0; q < n_cells; ++q) {
      const std::size_t c = static_cast<std::size_t>(q);
      const std::size_t o = v.offsets[c], e = v.offsets[c + 1];
      for (std::size_t k = o; k < e; ++k) {
        const std::size_t next = k + 1 < e ? k + 1 : o;
        cell_of[k] = c;
        edge[k] = std::hypot(v.x[next] - v.x[k], v.y[next] - v.y[k]);  // L_k: edge k → k+1
      }
      for (std::size_t k = o; k < e; ++k) ell[k] = 0.5 * (edge[k > o ? k - 1 : e - 1] + edge[k]);
    }
    S.assign(N, 0.0);
    px.assign(N, 0.0);
    py.assign(N, 0.0);
    count.assign(N, 0);
    rmin.assign(N, std::numeric_limits<double>::infinity());
  }

  struct Sums {
    double s = 0.0, fx = 0.0, fy = 0.0;
    double rmin = std::numeric_limits<double>::infinity();
    std::size_t k = 0;
  };

  void store(std::size_t m, const Sums& acc) {
    S[m] = acc.s;
    px[m] = acc.fx;
    py[m] = acc.fy;
    count[m] = acc.k;
    rmin[m] = acc.rmin;
  }

  // The walls' part (eq 4.13): W_m = Σ_walls W(s) and the normal force −W'(s) ℓ_m ∂s/∂X_m,
  // for every marker within the range of a wall of a non-periodic axis (walls at 0 and n).
  void add_walls() {
    const RepulsionParameters* rep = potential.wall_repulsion();
    if (!rep || (domain.periodic_x && domain.periodic_y)) return;
    const std::size_t N = v.x.size();
    W.assign(N, 0.0);
    const double Lx = domain.grid.nx, Ly = domain.grid.ny, d = rep->range;
    std::size_t near = 0;
    for (std::size_t m = 0; m < N; ++m) {
      bool touched = false;
      // One axis: walls at 0 (s = q, ∂s/∂q = 1) and at L (s = L − q, ∂s/∂q = −1).
      auto side = [&](double q, double L, double& force) {
        for (const double sign : {1.0, -1.0}) {
          const double gap = sign > 0 ? q : L - q;
          if (!(gap < d)) continue;
          if (!(gap > 0.0)) {
            if (beyond_wall == SIZE_MAX) {
              beyond_wall = m;
              beyond_wall_gap = gap;
            }
            continue;
          }
          double w = 0.0, dw = 0.0;
          wall_evaluate(*rep, gap, w, dw);
          W[m] += w;
          min_wall_gap = std::min(min_wall_gap, gap);
          force -= sign * dw * ell[m];
          touched = true;
        }
      };
      if (!domain.periodic_x) side(v.x[m], Lx, px[m]);
      if (!domain.periodic_y) side(v.y[m], Ly, py[m]);
      near += touched ? 1 : 0;
    }
    wall_markers = near;
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
    double e = 0.0;
    for (std::size_t m = 0; m < S.size(); ++m) e += ell[m] * S[m];  // E = ½ Σ ℓ_m S_m
    e *= 0.5;
    if (!W.empty()) {
      for (std::size_t m = 0; m < W.size(); ++m) e += ell[m] * W[m];  // + Σ ℓ_m W_m
    }
    return e;
  }

  // ∂E/∂ℓ_m: S_m, plus W_m with walls.
  double length_derivative(std::size_t m) const { return W.empty() ? S[m] : S[m] + W[m]; }

  // F_m = pair part + edge part (T_e = (S_e + S_{e+1})/2 along edge e), added to fx, fy.
  ContactStats finish(std::span<double> fx, std::span<double> fy, std::vector<double>* magnitude) const {
    check_coincident();
    const std::size_t N = S.size();
    if (fx.size() != N || fy.size() != N) throw std::invalid_argument("cell contacts: force arrays differ in size");
    if (magnitude) magnitude->assign(N, 0.0);
    const long long n_ll = static_cast<long long>(N);
#pragma omp parallel for schedule(static) if (N >= kParallelMarkers)
    for (long long i = 0; i < n_ll; ++i) {
      const std::size_t m = static_cast<std::size_t>(i);
      const std::size_t c = cell_of[m], o = v.offsets[c], e = v.offsets[c + 1];
      const std::size_t next = m + 1 < e ? m + 1 : o;
      const std::size_t prev = m > o ? m - 1 : e - 1;
      const double Tm = 0.5 * (length_derivative(m) + length_derivative(next));     // edge m: m → next
      const double Tp = 0.5 * (length_derivative(prev) + length_derivative(m));     // edge prev: prev → m
      const double um_x = (v.x[next] - v.x[m]) / edge[m], um_y = (v.y[next] - v.y[m]) / edge[m];
      const double up_x = (v.x[m] - v.x[prev]) / edge[prev], up_y = (v.y[m] - v.y[prev]) / edge[prev];
      const double gx = px[m] + Tm * um_x - Tp * up_x;
      const double gy = py[m] + Tm * um_y - Tp * up_y;
      fx[m] += gx;
      fy[m] += gy;
      if (magnitude) (*magnitude)[m] = std::hypot(gx, gy);
    }
    ContactStats st;
    st.wall_markers = wall_markers;
    st.min_wall_distance = min_wall_gap;
    for (std::size_t m = 0; m < N; ++m) st.min_pair_distance = std::min(st.min_pair_distance, rmin[m]);
    std::size_t pairs2 = 0;
    for (std::size_t m = 0; m < N; ++m) pairs2 += count[m];
    st.pairs = pairs2 / 2;
    st.energy = energy();
    if (magnitude) st.max_force = magnitude->empty() ? 0.0 : *std::max_element(magnitude->begin(), magnitude->end());
    return st;
  }
};

// Cell list over the domain: nb bins per axis of side n/nb ≥ r_c (at least 1 bin).
struct CellList {
  static constexpr std::size_t kMixed = SIZE_MAX;
  int nbx = 1, nby = 1;
  std::vector<std::size_t> start, items;  // markers of bin b: items[start[b] … start[b+1]), ascending
  std::vector<std::size_t> owner;         // per bin: the one cell of its markers, kMixed, or none (empty)

  static int bins(int n, double rc) {
    // floor(n / r_c), with a 1e-9 margin so round-off in the bin index can never put two
    // markers closer than r_c two bins apart.
    return std::max(1, static_cast<int>(std::floor(double(n) / (rc * (1.0 + 1e-9)))));
  }

  static int bin_of(double x, int n, int nb, bool periodic) {
    double t = x / n;
    if (periodic) t -= std::floor(t);
    // Clamped before the conversion (no overflow): on a non-periodic axis markers beyond a
    // wall join the edge bin; on a periodic one it only catches t·nb rounding up to nb.
    return static_cast<int>(std::clamp(std::floor(t * nb), 0.0, double(nb - 1)));
  }

  void build(const geometry::Domain& d, const MarkerView& v, std::vector<int>& bin) {
    const std::size_t N = v.x.size();
    bin.resize(N);
    start.assign(static_cast<std::size_t>(nbx * nby) + 1, 0);
    for (std::size_t m = 0; m < N; ++m) {
      bin[m] = bin_of(v.y[m], d.grid.ny, nby, d.periodic_y) * nbx + bin_of(v.x[m], d.grid.nx, nbx, d.periodic_x);
      ++start[static_cast<std::size_t>(bin[m]) + 1];
    }
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    items.resize(N);
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t m = 0; m < N; ++m) items[fill[static_cast<std::size_t>(bin[m])]++] = m;  // ascending per bin
  }

  // owner[b] for every bin: markers are ascending per bin and a cell's markers are one
  // index range, so the bin holds one cell iff its first and last marker share it.
  void find_owners(const std::vector<std::size_t>& cell_of) {
    const std::size_t bins = start.size() - 1;
    owner.assign(bins, 0);
    for (std::size_t b = 0; b < bins; ++b) {
      if (start[b] == start[b + 1]) continue;
      const std::size_t first = cell_of[items[start[b]]], last = cell_of[items[start[b + 1] - 1]];
      owner[b] = first == last ? first : kMixed;
    }
  }

  // Whether every marker of the (non-empty) bins `nb` belongs to one cell: then no marker
  // of them has a partner of another cell, and their pair sums stay zero.
  bool one_cell(const std::vector<int>& nb) const {
    std::size_t cell = kMixed;
    for (const int q : nb) {
      const std::size_t b = static_cast<std::size_t>(q);
      if (start[b] == start[b + 1]) continue;
      if (owner[b] == kMixed || (cell != kMixed && owner[b] != cell)) return false;
      cell = owner[b];
    }
    return true;
  }

  // The distinct bins within ±1 of (bx, by), wrapped on periodic axes, ascending.
  void neighbours(const geometry::Domain& d, int bx, int by, std::vector<int>& out) const {
    out.clear();
    if (bx >= 1 && bx + 1 < nbx && by >= 1 && by + 1 < nby) {  // inside: nine distinct bins, row by row
      for (int j = by - 1; j <= by + 1; ++j)
        for (int i = bx - 1; i <= bx + 1; ++i) out.push_back(j * nbx + i);
      return;
    }
    for (int oy = -1; oy <= 1; ++oy) {
      int j = by + oy;
      if (d.periodic_y) j = (j + nby) % nby;
      else if (j < 0 || j >= nby) continue;
      for (int ox = -1; ox <= 1; ++ox) {
        int i = bx + ox;
        if (d.periodic_x) i = (i + nbx) % nbx;
        else if (i < 0 || i >= nbx) continue;
        out.push_back(j * nbx + i);
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }
};

using detail::PairScratch;

struct SeparationInput {
  const double* cx;
  const double* cy;
  double xm, ym, Lx, Ly, ix, iy;
};

// X_m − X_n (minimum image on periodic axes, as image()) and r² for the candidates
// 0 … n − 1, the periodic flags fixed at compile time so that the loop is straight code
// the compiler vectorises (each lane does the scalar IEEE operations).
template <bool PX, bool PY>
void separations_of(const SeparationInput& in, std::size_t n, double* __restrict dx, double* __restrict dy,
                    double* __restrict r2) {
  const double* __restrict cx = in.cx;
  const double* __restrict cy = in.cy;
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) {
    const double ex = image(in.xm - cx[i], PX, in.Lx, in.ix);
    const double ey = image(in.ym - cy[i], PY, in.Ly, in.iy);
    dx[i] = ex;
    dy[i] = ey;
    r2[i] = ex * ex + ey * ey;
  }
}

struct PairInput {
  const double* mx;
  const double* my;
  const double* cx;
  const double* cy;
  double Lx, Ly, ix, iy;
};

// As separations_of, with marker m's position per entry (a range of several markers' lists).
template <bool PX, bool PY>
void pair_separations(const PairInput& in, std::size_t n, double* __restrict dx, double* __restrict dy,
                      double* __restrict r2) {
  const double* __restrict mx = in.mx;
  const double* __restrict my = in.my;
  const double* __restrict cx = in.cx;
  const double* __restrict cy = in.cy;
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) {
    const double ex = image(mx[i] - cx[i], PX, in.Lx, in.ix);
    const double ey = image(my[i] - cy[i], PY, in.Ly, in.iy);
    dx[i] = ex;
    dy[i] = ey;
    r2[i] = ex * ex + ey * ey;
  }
}

// Marker m against the candidates `cand` (ascending, none of m's own cell): their
// positions and lengths gathered, the separations and r² of each (vectorised). Returns
// the count; the values are in s.dx, s.dy, s.r2, s.cl.
std::size_t separations(const Engine& eng, std::size_t m, std::span<const std::size_t> cand, PairScratch& s) {
  const std::size_t n = cand.size();
  for (auto* buf : {&s.cx, &s.cy, &s.cl, &s.dx, &s.dy, &s.r2, &s.hr, &s.phi, &s.dphi, &s.w}) buf->resize(n);
  s.hits.resize(n);
  s.on.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.cx[i] = eng.v.x[cand[i]];
    s.cy[i] = eng.v.y[cand[i]];
    s.cl[i] = eng.ell[cand[i]];
  }
  const geometry::Domain& d = eng.domain;
  const SeparationInput in{s.cx.data(), s.cy.data(), eng.v.x[m], eng.v.y[m], double(d.grid.nx), double(d.grid.ny),
                           1.0 / double(d.grid.nx), 1.0 / double(d.grid.ny)};
  if (d.periodic_x && d.periodic_y) separations_of<true, true>(in, n, s.dx.data(), s.dy.data(), s.r2.data());
  else if (d.periodic_x) separations_of<true, false>(in, n, s.dx.data(), s.dy.data(), s.r2.data());
  else if (d.periodic_y) separations_of<false, true>(in, n, s.dx.data(), s.dy.data(), s.r2.data());
  else separations_of<false, false>(in, n, s.dx.data(), s.dy.data(), s.r2.data());
  return n;
}

// Pass 2: the candidates with 0 < r² < r_c², in candidate order (branch-free
// compaction into s.hits); r² = 0, two markers of different cells on one point, is
// reported after the parallel loop (no throw inside OpenMP). Returns their count.
std::size_t within_cutoff(Engine& eng, std::size_t n, PairScratch& s) {
  const double rc = eng.potential.cutoff(), rc2 = rc * rc;
  std::size_t k = 0;
  bool zero = false;
  std::size_t* __restrict h = s.hits.data();
  const double* __restrict r2 = s.r2.data();
  for (std::size_t i = 0; i < n; ++i) {
    h[k] = i;
    k += (r2[i] < rc2 && r2[i] > 0.0) ? 1 : 0;
    zero = zero || r2[i] == 0.0;
  }
  if (zero) eng.coincident.store(true, std::memory_order_relaxed);
  return k;
}

// Pass 3a: r, the pair law and the weight w = Φ'(ℓ_m ℓ_n)/r of the k pairs (vectorised;
// ContactPotential::evaluate_many). lm[i] is ℓ of candidate i's marker m.
void weights(const Engine& eng, std::size_t k, const double* lm_of, PairScratch& s) {
  {
    const std::size_t* __restrict h = s.hits.data();
    const double* __restrict r2 = s.r2.data();
    double* __restrict hr = s.hr.data();
#pragma omp simd
    for (std::size_t q = 0; q < k; ++q) hr[q] = std::sqrt(r2[h[q]]);
  }
  eng.potential.evaluate_many(s.hr.data(), k, s.phi.data(), s.dphi.data(), s.on.data());
  const std::size_t* __restrict h = s.hits.data();
  const double* __restrict cl = s.cl.data();
  const double* __restrict lm = lm_of;
  const double* __restrict hr = s.hr.data();
  const double* __restrict dphi = s.dphi.data();
  double* __restrict w = s.w.data();
#pragma omp simd
  for (std::size_t q = 0; q < k; ++q) w[q] = dphi[q] * (lm[h[q]] * cl[h[q]]) / hr[q];  // symmetric in (m, n) bit for bit
}

// Pass 3b: one marker's sums over the pairs q … (its hits below candidate index `end`), in
// candidate order; q is left at the next marker's first pair.
Engine::Sums ordered_sums(const PairScratch& s, std::size_t& q, std::size_t k, std::size_t end) {
  Engine::Sums acc;  // in registers
  for (; q < k && s.hits[q] < end; ++q) {
    if (!s.on[q]) continue;
    const std::size_t i = s.hits[q];
    acc.s += s.phi[q] * s.cl[i];  // S_m = Σ Φ ℓ_n
    acc.fx -= s.w[q] * s.dx[i];   // −Φ' ℓ_m ℓ_n (X_m − X_n)/r
    acc.fy -= s.w[q] * s.dy[i];
    acc.rmin = std::min(acc.rmin, s.hr[q]);
    ++acc.k;
  }
  return acc;
}

// The pair sums of marker m over `cand`: ascending marker indices, none of m's own cell,
// containing every marker of another cell within the cut-off (it may contain more):
// S_m, the pair force, the pair count and the closest partner. Three passes:
//   1. separations and r² (vectorised);
//   2. the candidates within the cut-off, in candidate order (within_cutoff);
//   3. the pair law and weights of those (weights), then the sums in candidate order
//      (ordered_sums).
// The order is ascending marker order for the pair lists (chunk_sums) and the brute force
// alike, and both use these passes, so the two give the same sums bit for bit, on any
// number of threads.
void pair_sums(Engine& eng, std::size_t m, std::span<const std::size_t> cand, PairScratch& s) {
  const std::size_t n = separations(eng, m, cand, s);
  const std::size_t k = within_cutoff(eng, n, s);
  s.ml.assign(n, eng.ell[m]);
  weights(eng, k, s.ml.data(), s);
  std::size_t q = 0;
  eng.store(m, ordered_sums(s, q, k, n));
}

}  // namespace

// The pair lists (Verlet lists, header): for each marker the markers of other cells within
// r_c + skin when they were built, ascending, found through a cell list of bins of side
// ≥ r_c + skin. Built in parallel over bins into per-thread buffers, then laid out per marker
// in marker order (CSR), the same lists for any thread count.
void CellContacts::build_pair_lists(const MarkerView& v, const std::vector<std::size_t>& cell_of) {
  const std::size_t N = v.x.size();
  const double reach = potential_.cutoff() + skin_, reach2 = reach * reach;
  CellList cl;
  cl.nbx = nbx_;
  cl.nby = nby_;
  std::vector<int> bin;
  cl.build(domain_, v, bin);
  cl.find_owners(cell_of);
  std::vector<std::size_t> begin(N, 0), length(N, 0);
  std::vector<int> thread_of(N, 0);
  const int nbins = nbx_ * nby_;
  const int threads = threads_forces(N) ? omp_get_max_threads() : 1;
  std::vector<std::vector<std::size_t>> found(static_cast<std::size_t>(threads));
  const geometry::Domain& d = domain_;
  const double Lx = d.grid.nx, Ly = d.grid.ny, ix = 1.0 / Lx, iy = 1.0 / Ly;
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    std::vector<std::size_t>& out = found[static_cast<std::size_t>(t)];
    out.clear();
    std::vector<int> nb;
    std::vector<std::size_t> cand, merged;
    std::vector<double> cx, cy, dx, dy, r2;
#pragma omp for schedule(dynamic, 64)
    for (int b = 0; b < nbins; ++b) {
      const std::size_t b0 = cl.start[static_cast<std::size_t>(b)], b1 = cl.start[static_cast<std::size_t>(b) + 1];
      if (b0 == b1) continue;
      cl.neighbours(d, b % nbx_, b / nbx_, nb);
      if (cl.one_cell(nb)) continue;  // one cell's markers only: empty lists
      // The bins' ascending runs merged into one ascending candidate list for the bin.
      cand.clear();
      for (const int q : nb) {
        const auto first = cl.items.begin() + static_cast<std::ptrdiff_t>(cl.start[static_cast<std::size_t>(q)]);
        const auto last = cl.items.begin() + static_cast<std::ptrdiff_t>(cl.start[static_cast<std::size_t>(q) + 1]);
        if (first == last) continue;
        merged.resize(cand.size() + static_cast<std::size_t>(last - first));
        std::merge(cand.begin(), cand.end(), first, last, merged.begin());
        cand.swap(merged);
      }
      const std::size_t n = cand.size();
      cx.resize(n);
      cy.resize(n);
      dx.resize(n);
      dy.resize(n);
      r2.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        cx[i] = v.x[cand[i]];
        cy[i] = v.y[cand[i]];
      }
      for (std::size_t k = b0; k < b1; ++k) {
        const std::size_t m = cl.items[k], c = cell_of[m];
        const SeparationInput in{cx.data(), cy.data(), v.x[m], v.y[m], Lx, Ly, ix, iy};
        if (d.periodic_x && d.periodic_y) separations_of<true, true>(in, n, dx.data(), dy.data(), r2.data());
        else if (d.periodic_x) separations_of<true, false>(in, n, dx.data(), dy.data(), r2.data());
        else if (d.periodic_y) separations_of<false, true>(in, n, dx.data(), dy.data(), r2.data());
        else separations_of<false, false>(in, n, dx.data(), dy.data(), r2.data());
        begin[m] = out.size();
        thread_of[m] = t;
        for (std::size_t i = 0; i < n; ++i) {
          if (r2[i] < reach2 && (cand[i] < v.offsets[c] || cand[i] >= v.offsets[c + 1])) out.push_back(cand[i]);
        }
        length[m] = out.size() - begin[m];
      }
    }
  }
  list_start_.assign(N + 1, 0);
  for (std::size_t m = 0; m < N; ++m) list_start_[m + 1] = list_start_[m] + length[m];
  list_.resize(list_start_[N]);
  for (std::size_t m = 0; m < N; ++m) {
    const std::vector<std::size_t>& src = found[static_cast<std::size_t>(thread_of[m])];
    std::copy_n(src.begin() + static_cast<std::ptrdiff_t>(begin[m]), length[m],
                list_.begin() + static_cast<std::ptrdiff_t>(list_start_[m]));
  }
  list_owner_.resize(list_.size());
  for (std::size_t m = 0; m < N; ++m)
    std::fill(list_owner_.begin() + static_cast<std::ptrdiff_t>(list_start_[m]),
              list_owner_.begin() + static_cast<std::ptrdiff_t>(list_start_[m + 1]), m);
  list_x_.assign(v.x.begin(), v.x.end());
  list_y_.assign(v.y.begin(), v.y.end());
  list_offsets_.assign(v.offsets.begin(), v.offsets.end());
  ++list_builds_;
}

// Whether the lists still hold every pair within r_c: the same cells, and no marker moved
// by skin/2 or more since they were built (two markers then close by less than the skin).
bool CellContacts::pair_lists_valid(const MarkerView& v) const {
  if (list_offsets_.size() != v.offsets.size() || !std::equal(list_offsets_.begin(), list_offsets_.end(), v.offsets.begin()))
    return false;
  const double limit2 = 0.25 * skin_ * skin_ * (1.0 - 1e-9);
  double worst = 0.0;
  const std::size_t N = v.x.size();
  for (std::size_t m = 0; m < N; ++m) {
    const double ex = v.x[m] - list_x_[m], ey = v.y[m] - list_y_[m];
    worst = std::max(worst, ex * ex + ey * ey);
  }
  return worst < limit2;
}

namespace {

// The pair sums of markers first … last − 1 over their pair lists, whose entries are one
// contiguous range of the CSR arrays: the same three passes as pair_sums, each over all of
// the range's entries at once (long vector loops instead of one short loop per marker),
// then each marker's sums over its own entries in list order. Per pair the same
// arithmetic as pair_sums, per marker the same order: the same bits.
void chunk_sums(Engine& eng, std::size_t first, std::size_t last, std::span<const std::size_t> start,
                std::span<const std::size_t> list, std::span<const std::size_t> owner, PairScratch& s) {
  const std::size_t e0 = start[first], n = start[last] - e0;
  if (n == 0) return;  // no partner: the sums keep their zeros
  for (auto* buf : {&s.cx, &s.cy, &s.cl, &s.dx, &s.dy, &s.r2, &s.hr, &s.phi, &s.dphi, &s.w, &s.mx, &s.my, &s.ml})
    buf->resize(n);
  s.hits.resize(n);
  s.on.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t p = list[e0 + i], m = owner[e0 + i];
    s.cx[i] = eng.v.x[p];
    s.cy[i] = eng.v.y[p];
    s.cl[i] = eng.ell[p];
    s.mx[i] = eng.v.x[m];
    s.my[i] = eng.v.y[m];
    s.ml[i] = eng.ell[m];
  }
  const geometry::Domain& d = eng.domain;
  const PairInput in{s.mx.data(), s.my.data(), s.cx.data(), s.cy.data(), double(d.grid.nx), double(d.grid.ny),
                     1.0 / double(d.grid.nx), 1.0 / double(d.grid.ny)};
  if (d.periodic_x && d.periodic_y) pair_separations<true, true>(in, n, s.dx.data(), s.dy.data(), s.r2.data());
  else if (d.periodic_x) pair_separations<true, false>(in, n, s.dx.data(), s.dy.data(), s.r2.data());
  else if (d.periodic_y) pair_separations<false, true>(in, n, s.dx.data(), s.dy.data(), s.r2.data());
  else pair_separations<false, false>(in, n, s.dx.data(), s.dy.data(), s.r2.data());
  const std::size_t k = within_cutoff(eng, n, s);
  weights(eng, k, s.ml.data(), s);
  std::size_t q = 0;
  for (std::size_t m = first; m < last; ++m) {
    const std::size_t end = start[m + 1] - e0;
    if (q < k && s.hits[q] < end) eng.store(m, ordered_sums(s, q, k, end));
  }
}

// Every marker's pair sums over its pair list, chunks of markers over the threads.
void run_pair_lists(Engine& eng, std::span<const std::size_t> start, std::span<const std::size_t> list,
                    std::span<const std::size_t> owner) {
  const std::size_t N = eng.v.x.size();
  const long long chunks = static_cast<long long>((N + 63) / 64);
  // Each thread its own scratch, kept in the workspace (a team of one inside a parallel region
  // of the caller uses the first).
  if (eng.per_thread.size() < static_cast<std::size_t>(omp_get_max_threads()))
    eng.per_thread.resize(static_cast<std::size_t>(omp_get_max_threads()));
#pragma omp parallel if (N >= kParallelMarkers)
  {
    PairScratch& s = eng.per_thread[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 4)
    for (long long q = 0; q < chunks; ++q) {
      const std::size_t first = static_cast<std::size_t>(q) * 64, last = std::min(N, first + 64);
      chunk_sums(eng, first, last, start, list, owner, s);
    }
  }
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

CellContacts::CellContacts(const geometry::Domain& domain, const ContactLaw& law) : domain_(domain), potential_(law) {
  const double rc = potential_.cutoff();
  check_periodic_cutoff(domain, rc);
  // The skin: kSkin, at most a quarter of the cut-off, and small enough that r_c + skin
  // stays below half of every periodic side (the minimum image stays the only image).
  skin_ = std::min(kSkin, 0.25 * rc);
  if (domain.periodic_x) skin_ = std::min(skin_, 0.99 * (0.5 * domain.grid.nx - rc));
  if (domain.periodic_y) skin_ = std::min(skin_, 0.99 * (0.5 * domain.grid.ny - rc));
  skin_ = std::max(skin_, 0.0);
  nbx_ = CellList::bins(domain.grid.nx, rc + skin_);
  nby_ = CellList::bins(domain.grid.ny, rc + skin_);
}

// The pair sums of every marker (E is this file's Engine): the lists rebuilt when needed.
template <class E>
void CellContacts::pair_sums_all(E& eng) {
  if (!pair_lists_valid(eng.v)) build_pair_lists(eng.v, eng.cell_of);
  run_pair_lists(eng, list_start_, list_, list_owner_);
}

ContactStats CellContacts::add_forces(const MarkerView& markers, std::span<double> fx, std::span<double> fy) {
  Engine eng(domain_, potential_, markers, work_);
  pair_sums_all(eng);
  eng.add_walls();
  return eng.finish(fx, fy, &magnitude_);
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
  const double fmax = mag.empty() ? 0.0 : *std::max_element(mag.begin(), mag.end());
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
  return eng.finish(fx, fy, &mag);
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
