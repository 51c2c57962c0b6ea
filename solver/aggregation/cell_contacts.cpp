#include "aggregation/cell_contacts.hpp"

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

// The shared arithmetic of the cell-list and brute-force paths (see the header).
// pair_sums(m, cand) takes, for marker m, marker indices in ASCENDING order containing
// every marker of another cell within the cut-off (it may contain more).
struct Engine {
  const geometry::Domain& domain;
  const ContactPotential& potential;
  const MarkerView& v;
  std::vector<std::size_t> cell_of;
  std::vector<double> edge, ell, S, px, py, rmin;
  std::vector<double> W;  // W(s_m) summed over the walls (eq 4.13); empty without wall repulsion
  std::size_t wall_markers = 0;
  double min_wall_gap = std::numeric_limits<double>::infinity();
  std::vector<double> box_cx, box_cy, box_hx, box_hy;  // per-cell bounding box: centre, half-widths
  std::vector<std::size_t> count;
  std::atomic<bool> coincident{false};
  std::size_t beyond_wall = SIZE_MAX;  // the first marker on or beyond a wall (add_walls is serial)
  double beyond_wall_gap = 0.0;
  bool use_boxes = true;  // bounding-box block skip (cell lists); the brute force tests every pair

  Engine(const geometry::Domain& d, const ContactPotential& p, const MarkerView& view) : domain(d), potential(p), v(view) {
    check_view(v);
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
    const std::size_t cells = v.offsets.size() - 1;
    box_cx.resize(cells);
    box_cy.resize(cells);
    box_hx.resize(cells);
    box_hy.resize(cells);
    for (std::size_t c = 0; c < cells; ++c) {
      const auto xs = std::minmax_element(v.x.begin() + static_cast<std::ptrdiff_t>(v.offsets[c]),
                                          v.x.begin() + static_cast<std::ptrdiff_t>(v.offsets[c + 1]));
      const auto ys = std::minmax_element(v.y.begin() + static_cast<std::ptrdiff_t>(v.offsets[c]),
                                          v.y.begin() + static_cast<std::ptrdiff_t>(v.offsets[c + 1]));
      box_cx[c] = 0.5 * (*xs.first + *xs.second);
      box_hx[c] = 0.5 * (*xs.second - *xs.first) * (1.0 + 1e-12);
      box_cy[c] = 0.5 * (*ys.first + *ys.second);
      box_hy[c] = 0.5 * (*ys.second - *ys.first) * (1.0 + 1e-12);
    }
    S.assign(N, 0.0);
    px.assign(N, 0.0);
    py.assign(N, 0.0);
    count.assign(N, 0);
    rmin.assign(N, std::numeric_limits<double>::infinity());
  }

  // Pair sums of marker m over its candidate list: S_m, the pair force, the pair count.
  // The candidates are ascending, so marker m's own cell (a contiguous index range) is one
  // contiguous block of them: skipped by two binary searches instead of a test per pair
  // (same pairs, same order as testing each).
  void pair_sums(std::size_t m, std::span<const std::size_t> cand) {
    const std::size_t cm = cell_of[m];
    const auto own_begin = std::lower_bound(cand.begin(), cand.end(), v.offsets[cm]);
    const auto own_end = std::lower_bound(own_begin, cand.end(), v.offsets[cm + 1]);
    Sums acc;
    accumulate(m, cand.subspan(0, static_cast<std::size_t>(own_begin - cand.begin())), acc);
    accumulate(m, cand.subspan(static_cast<std::size_t>(own_end - cand.begin())), acc);
    S[m] = acc.s;
    px[m] = acc.fx;
    py[m] = acc.fy;
    count[m] = acc.k;
    rmin[m] = acc.rmin;
  }

  struct Sums {
    double s = 0.0, fx = 0.0, fy = 0.0;
    double rmin = std::numeric_limits<double>::infinity();
    std::size_t k = 0;
  };

  // The candidates of one cell form a contiguous block of the (ascending) list. A block
  // is skipped whole when the cell's bounding box is beyond r_c of marker m: the
  // minimum-image distance d(a) is 1-Lipschitz, so |X_m − X_n| ≥ d(X_m − box centre) −
  // half-width per axis for every marker n of the cell. Skipped pairs are ones the test
  // r² < r_c² would drop anyway (margin 1e-9 against round-off), so the sums and their
  // order are unchanged: still bitwise the brute-force result.
  void accumulate(std::size_t m, std::span<const std::size_t> cand, Sums& sums) {
    Sums acc = sums;  // in registers: the loop's stores would otherwise go through memory
    const double Lx = domain.grid.nx, Ly = domain.grid.ny, ix = 1.0 / Lx, iy = 1.0 / Ly;
    const bool perx = domain.periodic_x, pery = domain.periodic_y;
    const double rc = potential.cutoff(), rc2 = rc * rc, skip2 = rc2 * (1.0 + 1e-9);
    const double xm = v.x[m], ym = v.y[m], lm = ell[m];
    std::size_t i = 0;
    while (i < cand.size()) {
      const std::size_t c = cell_of[cand[i]];
      const double gx = std::max(std::abs(image(xm - box_cx[c], perx, Lx, ix)) - box_hx[c], 0.0);
      const double gy = std::max(std::abs(image(ym - box_cy[c], pery, Ly, iy)) - box_hy[c], 0.0);
      const std::size_t end = static_cast<std::size_t>(
          std::lower_bound(cand.begin() + static_cast<std::ptrdiff_t>(i), cand.end(), v.offsets[c + 1]) - cand.begin());
      if (use_boxes && gx * gx + gy * gy >= skip2) {
        i = end;
        continue;
      }
      for (; i < end; ++i) {
        const std::size_t n = cand[i];
        const double dx = image(xm - v.x[n], perx, Lx, ix);
        const double dy = image(ym - v.y[n], pery, Ly, iy);
        const double r2 = dx * dx + dy * dy;
        if (!(r2 < rc2)) continue;
        const double r = std::sqrt(r2);
        if (!(r > 0.0)) {  // no direction: reported after the parallel loop (no throw inside OpenMP)
          coincident.store(true, std::memory_order_relaxed);
          continue;
        }
        double phi = 0.0, dphi = 0.0;
        if (!potential.evaluate(r, phi, dphi)) continue;
        acc.s += phi * ell[n];                        // S_m = Σ Φ ℓ_n
        const double w = dphi * (lm * ell[n]) / r;    // symmetric in (m, n) bit for bit
        acc.fx -= w * dx;                             // −Φ' ℓ_m ℓ_n (X_m − X_n)/r
        acc.fy -= w * dy;
        acc.rmin = std::min(acc.rmin, r);
        ++acc.k;
      }
    }
    sums = acc;
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

void run_cell_list(Engine& eng, const geometry::Domain& d, int nbx, int nby) {
  CellList cl;
  cl.nbx = nbx;
  cl.nby = nby;
  std::vector<int> bin;
  cl.build(d, eng.v, bin);
  cl.find_owners(eng.cell_of);
  const int nbins = nbx * nby;
#pragma omp parallel if (eng.v.x.size() >= kParallelMarkers)
  {
    std::vector<int> nb;
    std::vector<std::size_t> cand, merged;
#pragma omp for schedule(dynamic, 64)
    for (int b = 0; b < nbins; ++b) {
      const std::size_t b0 = cl.start[static_cast<std::size_t>(b)], b1 = cl.start[static_cast<std::size_t>(b) + 1];
      if (b0 == b1) continue;
      cl.neighbours(d, b % nbx, b / nbx, nb);
      // A neighbourhood of one cell's markers only (most of them at a short range): nothing
      // to add, the sums keep their initial zeros (the same bits as visiting them).
      if (cl.one_cell(nb)) continue;
      // One ascending candidate list serves every marker of bin b (ascending = brute-force
      // order): the bins' ascending runs merged one after the other into reused buffers
      // (linear per run, no allocation once the buffers have grown; the same order as
      // sorting them, so the same bits).
      cand.clear();
      for (const int q : nb) {
        const auto first = cl.items.begin() + static_cast<std::ptrdiff_t>(cl.start[static_cast<std::size_t>(q)]);
        const auto last = cl.items.begin() + static_cast<std::ptrdiff_t>(cl.start[static_cast<std::size_t>(q) + 1]);
        if (first == last) continue;
        merged.resize(cand.size() + static_cast<std::size_t>(last - first));
        std::merge(cand.begin(), cand.end(), first, last, merged.begin());
        cand.swap(merged);
      }
      for (std::size_t k = b0; k < b1; ++k) eng.pair_sums(cl.items[k], cand);
    }
  }
}

void run_brute_force(Engine& eng) {
  eng.use_boxes = false;
  const std::size_t N = eng.v.x.size();
  std::vector<std::size_t> all(N);
  std::iota(all.begin(), all.end(), std::size_t{0});
  const long long n_ll = static_cast<long long>(N);
#pragma omp parallel for schedule(static) if (N >= kParallelMarkers)
  for (long long i = 0; i < n_ll; ++i) eng.pair_sums(static_cast<std::size_t>(i), all);
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
  check_periodic_cutoff(domain, potential_.cutoff());
  nbx_ = CellList::bins(domain.grid.nx, potential_.cutoff());
  nby_ = CellList::bins(domain.grid.ny, potential_.cutoff());
}

ContactStats CellContacts::add_forces(const MarkerView& markers, std::span<double> fx, std::span<double> fy) {
  Engine eng(domain_, potential_, markers);
  run_cell_list(eng, domain_, nbx_, nby_);
  eng.add_walls();
  return eng.finish(fx, fy, &magnitude_);
}

double CellContacts::energy(const MarkerView& markers) const {
  Engine eng(domain_, potential_, markers);
  run_cell_list(eng, domain_, nbx_, nby_);
  eng.add_walls();
  return eng.energy();
}

ContactStats CellContacts::add_forces(membrane::ImmersedCells& cells) {
  check_same_domain(domain_, cells.transfer().domain());
  const std::vector<std::size_t> offsets = cell_offsets(cells);
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
  Engine eng(domain, potential, markers);
  run_brute_force(eng);
  eng.add_walls();
  std::vector<double> mag;
  return eng.finish(fx, fy, &mag);
}

double energy_brute_force(const geometry::Domain& domain, const ContactLaw& law, const MarkerView& markers) {
  const ContactPotential potential(law);
  check_periodic_cutoff(domain, potential.cutoff());
  Engine eng(domain, potential, markers);
  run_brute_force(eng);
  eng.add_walls();
  return eng.energy();
}

}  // namespace erythro::aggregation
