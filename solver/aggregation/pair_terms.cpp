#include "aggregation/pair_terms.hpp"

#include <algorithm>

namespace erythro::aggregation {

namespace {

// Pass 1 with the periodic flags fixed at compile time: straight code the compiler vectorises.
template <bool PX, bool PY>
void separations_of(const geometry::Domain& d, std::size_t n, PairScratch& s) {
  const double Lx = d.grid.nx, Ly = d.grid.ny, ix = 1.0 / Lx, iy = 1.0 / Ly;
  const double* __restrict mx = s.mx.data();
  const double* __restrict my = s.my.data();
  const double* __restrict cx = s.cx.data();
  const double* __restrict cy = s.cy.data();
  double* __restrict dx = s.dx.data();
  double* __restrict dy = s.dy.data();
  double* __restrict r2 = s.r2.data();
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) {
    const double ex = image(mx[i] - cx[i], PX, Lx, ix);
    const double ey = image(my[i] - cy[i], PY, Ly, iy);
    dx[i] = ex;
    dy[i] = ey;
    r2[i] = ex * ex + ey * ey;
  }
}

}  // namespace

void PairScratch::hold(std::size_t n) {
  if (on.size() >= n) return;  // only grow: a shrink and regrow would zero the regrown tail for nothing
  for (auto* buf : {&mx, &my, &ml, &cx, &cy, &cl, &dx, &dy, &r2, &hr, &phi, &dphi, &w}) buf->resize(n);
  hits.resize(n);
  on.resize(n);
}

void pair_separations(const geometry::Domain& d, std::size_t n, PairScratch& s) {
  if (d.periodic_x && d.periodic_y) separations_of<true, true>(d, n, s);
  else if (d.periodic_x) separations_of<true, false>(d, n, s);
  else if (d.periodic_y) separations_of<false, true>(d, n, s);
  else separations_of<false, false>(d, n, s);
}

std::size_t pairs_within(double rc2, std::size_t n, PairScratch& s, bool& coincident) {
  std::size_t k = 0;
  bool zero = false;
  std::size_t* __restrict h = s.hits.data();
  const double* __restrict r2 = s.r2.data();
  for (std::size_t i = 0; i < n; ++i) {  // branch-free compaction: the order is kept
    h[k] = i;
    k += (r2[i] < rc2 && r2[i] > 0.0) ? 1 : 0;
    zero = zero || r2[i] == 0.0;
  }
  if (zero) coincident = true;
  return k;
}

void pair_weights(const ContactPotential& potential, std::size_t k, PairScratch& s) {
  {
    const std::size_t* __restrict h = s.hits.data();
    const double* __restrict r2 = s.r2.data();
    double* __restrict hr = s.hr.data();
#pragma omp simd
    for (std::size_t q = 0; q < k; ++q) hr[q] = std::sqrt(r2[h[q]]);
  }
  potential.evaluate_many(s.hr.data(), k, s.phi.data(), s.dphi.data(), s.on.data());
  const std::size_t* __restrict h = s.hits.data();
  const double* __restrict cl = s.cl.data();
  const double* __restrict ml = s.ml.data();
  const double* __restrict hr = s.hr.data();
  const double* __restrict dphi = s.dphi.data();
  double* __restrict w = s.w.data();
#pragma omp simd
  for (std::size_t q = 0; q < k; ++q) w[q] = pair_weight(dphi[q], ml[h[q]], cl[h[q]], hr[q]);
}

std::size_t evaluate_pairs(const geometry::Domain& d, const ContactPotential& potential, std::size_t n,
                           PairScratch& s, bool& coincident) {
  pair_separations(d, n, s);
  const double rc = potential.cutoff();
  const std::size_t k = pairs_within(rc * rc, n, s, coincident);
  pair_weights(potential, k, s);
  return k;
}

PairSums marker_sums(const PairScratch& s, std::size_t& q, std::size_t k, std::size_t end) {
  PairSums acc;  // in registers
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

}  // namespace erythro::aggregation
