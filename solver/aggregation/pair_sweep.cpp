#include "aggregation/pair_sweep.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/select_bits.hpp"

namespace erythro::aggregation {

namespace {

constexpr std::size_t kChunk = 64;  // visited markers whose runs are evaluated as one batch

// The run's separations X_m − X_n (minimum image), r², ℓ_m and ℓ_n into the batch at `at`: a
// straight loop over the run's stretch of the marker arrays (the operations of
// pair_separations, lane by lane).
template <bool PX, bool PY>
void run_separations(const geometry::Domain& d, const SweepArrays& a, const SweepScratch::Run& run, SweepScratch& s) {
  const double Lx = d.grid.nx, Ly = d.grid.ny, ix = 1.0 / Lx, iy = 1.0 / Ly;
  const double xm = a.x[run.marker], ym = a.y[run.marker], lm = a.ell[run.marker];
  const double* __restrict xn = a.x.data() + run.first;
  const double* __restrict yn = a.y.data() + run.first;
  const double* __restrict ln = a.ell.data() + run.first;
  double* __restrict dx = s.dx.data() + run.at;
  double* __restrict dy = s.dy.data() + run.at;
  double* __restrict r2 = s.r2.data() + run.at;
  double* __restrict ml = s.ml.data() + run.at;
  double* __restrict cl = s.cl.data() + run.at;
#pragma omp simd
  for (std::size_t k = 0; k < run.length; ++k) {
    const double ex = image(xm - xn[k], PX, Lx, ix);
    const double ey = image(ym - yn[k], PY, Ly, iy);
    dx[k] = ex;
    dy[k] = ey;
    r2[k] = ex * ex + ey * ey;
    ml[k] = lm;
    cl[k] = ln[k];
  }
}

// The pair law over the batch's n entries (pair_weights' operations): r where 0 < r² < r_c²,
// else r_c, for which the potential gives no interaction; then Φ, Φ', `on` and w = Φ'(ℓ_m ℓ_n)/r.
// Returns whether some r² is 0 (two markers of different cells on one point).
bool batch_terms(const ContactPotential& potential, std::size_t n, SweepScratch& s) {
  const double rc = potential.cutoff(), rc2 = rc * rc;
  int zero = 0;  // an int: a bool's reduction kept the loop scalar
  {
    const double* __restrict r2 = s.r2.data();
    double* __restrict hr = s.hr.data();
#pragma omp simd reduction(| : zero)
    for (std::size_t q = 0; q < n; ++q) {
      const double v = r2[q];
      zero |= v == 0.0 ? 1 : 0;
      const double r = std::sqrt(v);
      hr[q] = v < rc2 && v > 0.0 ? r : rc;
    }
  }
  potential.evaluate_many(s.hr.data(), n, s.phi.data(), s.dphi.data(), s.on.data());
  const double* __restrict ml = s.ml.data();
  const double* __restrict cl = s.cl.data();
  const double* __restrict hr = s.hr.data();
  const double* __restrict dphi = s.dphi.data();
  double* __restrict w = s.w.data();
#pragma omp simd
  for (std::size_t q = 0; q < n; ++q) w[q] = pair_weight(dphi[q], ml[q], cl[q], hr[q]);
  // The marker's terms, where the pair does not interact the values that leave each sum as it
  // is bit for bit (x + (−0) = x and x − (+0) = x for every x, −0 included; min(x, +∞) = x).
  const double* __restrict phi = s.phi.data();
  const double* __restrict dx = s.dx.data();
  const double* __restrict dy = s.dy.data();
  const unsigned char* __restrict on = s.on.data();
  double* __restrict ts = s.ts.data();
  double* __restrict tx = s.tx.data();
  double* __restrict ty = s.ty.data();
  double* __restrict tr = s.tr.data();
#pragma omp simd
  for (std::size_t q = 0; q < n; ++q) {
    const bool pair = on[q] != 0;  // c ? a : b through the bits: vectorised on AVX2 too (select_bits.hpp)
    ts[q] = numeric::select_bits(pair, phi[q] * cl[q], -0.0);  // S_m = Σ Φ ℓ_n
    tx[q] = numeric::select_bits(pair, w[q] * dx[q], 0.0);     // −Φ' ℓ_m ℓ_n (X_m − X_n)/r, subtracted
    ty[q] = numeric::select_bits(pair, w[q] * dy[q], 0.0);
    tr[q] = numeric::select_bits(pair, hr[q], std::numeric_limits<double>::infinity());
  }
  return zero != 0;
}

// The run's pairs to its partners (each partner once in a run: the lanes never meet): S_n += Φ ℓ_m,
// the pair force −Φ' ℓ_m ℓ_n (X_n − X_m)/r with X_n − X_m = −dx, the closest partner and the count,
// each only where the pair interacts: where batch_terms left a finite closest distance tr (its +∞
// marks a pair that does not interact). Only eight-byte elements in the loop: a byte flag there
// set the vector length to 32 lanes, so a run shorter than 32 (most runs) took the scalar tail.
void add_to_partners(const SweepArrays& a, const SweepScratch& s, const SweepScratch::Run& run) {
  double* __restrict S = a.S.data() + run.first;
  double* __restrict px = a.px.data() + run.first;
  double* __restrict py = a.py.data() + run.first;
  double* __restrict rmin = a.rmin.data() + run.first;
  std::size_t* __restrict count = a.count.data() + run.first;
  const double* __restrict phi = s.phi.data() + run.at;
  const double* __restrict ml = s.ml.data() + run.at;
  const double* __restrict w = s.w.data() + run.at;
  const double* __restrict dx = s.dx.data() + run.at;
  const double* __restrict dy = s.dy.data() + run.at;
  const double* __restrict hr = s.hr.data() + run.at;
  const double* __restrict tr = s.tr.data() + run.at;
  constexpr double kNoPair = std::numeric_limits<double>::infinity();
#pragma omp simd
  for (std::size_t k = 0; k < run.length; ++k) {
    const bool pair = tr[k] != kNoPair;  // c ? a : b through the bits: vectorised on AVX2 too (select_bits.hpp)
    S[k] = numeric::select_bits(pair, S[k] + phi[k] * ml[k], S[k]);
    px[k] = numeric::select_bits(pair, px[k] - w[k] * (-dx[k]), px[k]);
    py[k] = numeric::select_bits(pair, py[k] - w[k] * (-dy[k]), py[k]);
    rmin[k] = numeric::select_bits(pair, std::min(rmin[k], hr[k]), rmin[k]);
    count[k] += pair ? 1 : 0;
  }
}

// Entry q's terms added to a marker's sums (batch_terms: a pair that does not interact adds
// nothing). Inlined by force: two markers' sums advance side by side (add_to_markers).
[[gnu::always_inline]] inline void add_entry(const SweepScratch& s, std::size_t q, PairSums& acc) {
  acc.s += s.ts[q];
  acc.fx -= s.tx[q];
  acc.fy -= s.ty[q];
  acc.rmin = std::min(acc.rmin, s.tr[q]);
  acc.k += s.on[q];
}

PairSums sums_of(const SweepArrays& a, std::size_t m) { return {a.S[m], a.px[m], a.py[m], a.rmin[m], a.count[m]}; }

void store_sums(const SweepArrays& a, std::size_t m, const PairSums& acc) {
  a.S[m] = acc.s;
  a.px[m] = acc.fx;
  a.py[m] = acc.fy;
  a.rmin[m] = acc.rmin;
  a.count[m] = acc.k;
}

// The own markers' sums over their entries, two markers at a time: each marker's additions stay
// in its order, and the two chains of additions overlap in the processor.
void add_to_markers(const SweepArrays& a, const SweepScratch& s) {
  const std::vector<SweepScratch::OwnMarker>& own = s.own;
  std::size_t j = 0;
  for (; j + 1 < own.size(); j += 2) {
    const SweepScratch::OwnMarker& u = own[j];
    const SweepScratch::OwnMarker& v = own[j + 1];
    PairSums A = sums_of(a, u.m), B = sums_of(a, v.m);
    const std::size_t nu = u.q1 - u.q0, nv = v.q1 - v.q0, both = std::min(nu, nv);
    for (std::size_t k = 0; k < both; ++k) {
      add_entry(s, u.q0 + k, A);
      add_entry(s, v.q0 + k, B);
    }
    for (std::size_t k = both; k < nu; ++k) add_entry(s, u.q0 + k, A);
    for (std::size_t k = both; k < nv; ++k) add_entry(s, v.q0 + k, B);
    store_sums(a, u.m, A);
    store_sums(a, v.m, B);
  }
  if (j < own.size()) {
    const SweepScratch::OwnMarker& u = own[j];
    PairSums A = sums_of(a, u.m);
    for (std::size_t q = u.q0; q < u.q1; ++q) add_entry(s, q, A);
    store_sums(a, u.m, A);
  }
}

// Into s: the runs of the visits first … last − 1 that thread t evaluates (an own marker's
// runs all; another thread's marker's runs whose partners are t's), their places in the batch
// and each visit's end among them. Returns the batch's entry count. kOneOwner: every marker is
// t's (one thread), no owner is looked up.
template <bool kOneOwner>
std::size_t collect_runs(const PairLists& lists, const SweepOwners& owners, unsigned t,
                         std::span<const std::size_t> visits, std::size_t first, std::size_t last, SweepScratch& s) {
  const std::span<const std::size_t> run_start = lists.run_start(), run_first = lists.run_first(),
                                     run_length = lists.run_length();
  const std::span<const unsigned> owner = owners.owner();
  s.runs.clear();
  s.run_ends.resize(last - first);
  std::size_t n = 0;
  for (std::size_t i = first; i < last; ++i) {
    const std::size_t m = kOneOwner ? i : visits[i];  // one owner visits every marker, in order
    const bool own = kOneOwner || owner[m] == t;
    for (std::size_t r = run_start[m]; r < run_start[m + 1]; ++r) {
      const bool to_partners = kOneOwner || owner[run_first[r]] == t;  // a run lies in one cell
      if (!own && !to_partners) continue;
      s.runs.push_back({m, run_first[r], run_length[r], n, to_partners});
      n += run_length[r];
    }
    s.run_ends[i - first] = s.runs.size();
  }
  return n;
}

// Thread t's visits in ascending order (pair_sweep.hpp): an own marker's pairs above it to the
// marker and to its partners of thread t; another thread's marker's pairs to its partners.
template <bool kOneOwner, bool PX, bool PY>
void sweep_owner(const geometry::Domain& d, const ContactPotential& potential, const PairLists& lists,
                 const SweepOwners& owners, const SweepArrays& a, unsigned t, SweepScratch& s, bool& coincident) {
  // One owner visits every marker in order and looks nothing up (its owners may be empty).
  const std::span<const std::size_t> visits =
      kOneOwner ? std::span<const std::size_t>{} : owners.visits(static_cast<int>(t));
  const std::span<const unsigned> owner = owners.owner();
  const std::size_t count = kOneOwner ? a.x.size() : visits.size();
  for (std::size_t first = 0; first < count; first += kChunk) {
    const std::size_t last = std::min(count, first + kChunk);
    const std::size_t n = collect_runs<kOneOwner>(lists, owners, t, visits, first, last, s);
    if (n == 0) continue;  // no pair above these markers: their sums are complete
    s.hold(n);
    for (const SweepScratch::Run& run : s.runs) run_separations<PX, PY>(d, a, run, s);
    if (batch_terms(potential, n, s)) coincident = true;
    // First every pair to its partners, in the order of the visits; a partner lies above its
    // marker, so each marker of the batch then holds the pairs of every marker below it.
    s.own.clear();
    std::size_t r = 0;
    for (std::size_t i = first; i < last; ++i) {
      const std::size_t end = s.run_ends[i - first];
      if (r == end) continue;
      const std::size_t m = kOneOwner ? i : visits[i];
      if (kOneOwner || owner[m] == t)  // an own marker's runs are all in the batch, one stretch
        s.own.push_back({m, s.runs[r].at, s.runs[end - 1].at + s.runs[end - 1].length});
      for (; r < end; ++r)
        if (s.runs[r].to_partners) add_to_partners(a, s, s.runs[r]);  // else the partners' thread adds them
    }
    // Then the own markers' sums over their pairs above them.
    add_to_markers(a, s);
  }
}

template <bool kOneOwner>
void sweep_owner_in(const geometry::Domain& d, const ContactPotential& potential, const PairLists& lists,
                    const SweepOwners& owners, const SweepArrays& a, unsigned t, SweepScratch& s, bool& coincident) {
  if (d.periodic_x && d.periodic_y)
    sweep_owner<kOneOwner, true, true>(d, potential, lists, owners, a, t, s, coincident);
  else if (d.periodic_x)
    sweep_owner<kOneOwner, true, false>(d, potential, lists, owners, a, t, s, coincident);
  else if (d.periodic_y)
    sweep_owner<kOneOwner, false, true>(d, potential, lists, owners, a, t, s, coincident);
  else
    sweep_owner<kOneOwner, false, false>(d, potential, lists, owners, a, t, s, coincident);
}

}  // namespace

void SweepScratch::hold(std::size_t n) {
  if (on.size() >= n) return;  // the batches differ in size: a shrink and regrow would zero the regrown tail
  for (auto* buf : {&dx, &dy, &r2, &hr, &ml, &cl, &phi, &dphi, &w, &ts, &tx, &ty, &tr}) buf->resize(n);
  on.resize(n);
}

bool sweep_pair_lists(const geometry::Domain& domain, const ContactPotential& potential, const PairLists& lists,
                      const SweepOwners& owners, int threads, const SweepArrays& a,
                      std::vector<SweepScratch>& per_thread) {
  threads = std::max(threads, 1);
  if (per_thread.size() < static_cast<std::size_t>(threads)) per_thread.resize(static_cast<std::size_t>(threads));
  // Every thread's buffers as large as the largest batch any thread has held: other owners
  // next time (the slabs move with the cells) then need no new room.
  std::size_t most = 0;
  for (const SweepScratch& s : per_thread) most = std::max(most, s.on.size());
  for (SweepScratch& s : per_thread) s.hold(most);
  bool coincident = false;
#pragma omp parallel num_threads(threads) if (threads > 1) reduction(|| : coincident)
  {
    // Each owner's sweep writes only its own markers' sums: a team smaller than asked for
    // takes the owners in turns (the owners change the work, not the bits).
    const int i = omp_get_thread_num(), team = omp_get_num_threads();
    SweepScratch& s = per_thread[static_cast<std::size_t>(i)];
    if (threads == 1)
      sweep_owner_in<true>(domain, potential, lists, owners, a, 0, s, coincident);
    else
      for (int t = i; t < threads; t += team)
        sweep_owner_in<false>(domain, potential, lists, owners, a, static_cast<unsigned>(t), s, coincident);
  }
  return coincident;
}

}  // namespace erythro::aggregation
