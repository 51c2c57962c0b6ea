#include "taylor_green_probe.hpp"

#include <cmath>
#include <limits>

#include "lattice/d2q9.hpp"

namespace erythro::vv {

TaylorGreenErrorProbe::TaylorGreenErrorProbe(const fluid::FluidLattice& lattice, fluid::FlowField exact0, double nu,
                                             double k, long steps)
    : lattice_(lattice), exact0_(std::move(exact0)), nu_(nu), k_(k), steps_(steps) {}

void TaylorGreenErrorProbe::declare(std::vector<sim::SeriesInfo>& series) const {
  series.push_back({"tg_error_u", "", "relative L2 velocity error against the exact Taylor-Green vortex"});
  series.push_back({"tg_error_p", "", "relative L2 pressure error against the exact Taylor-Green vortex"});
  series.push_back({"tg_window_error_u", "", "relative space-time L2 velocity error over t in [3T/4, T]"});
  series.push_back({"tg_window_error_p", "", "relative space-time L2 pressure error over t in [3T/4, T]"});
}

TaylorGreenErrorProbe::Sums TaylorGreenErrorProbe::sums(const fluid::Moments& m, long s) const {
  const double fu = std::exp(-2.0 * nu_ * k_ * k_ * double(s)), fp = fu * fu;
  Sums r;
  for (std::size_t n = 0; n < m.rho.size(); ++n) {
    const double ue = exact0_.ux[n] * fu, ve = exact0_.uy[n] * fu, pe = d2q9::cs2 * (exact0_.rho[n] - 1.0) * fp;
    const double pn = d2q9::cs2 * (m.rho[n] - 1.0);
    r.du2 += (m.ux[n] - ue) * (m.ux[n] - ue) + (m.uy[n] - ve) * (m.uy[n] - ve);
    r.u2 += ue * ue + ve * ve;
    r.dp2 += (pn - pe) * (pn - pe);
    r.p2 += pe * pe;
  }
  return r;
}

void TaylorGreenErrorProbe::register_stages(sim::TimeLoop& loop) {
  // Step n takes the state to s = n + 1; the window is 4s >= 3T.
  const long first_s = (3 * steps_ + 3) / 4;
  loop.add(
      sim::Phase::observe, "taylor_green_window",
      [this](long n) {
        const Sums s = sums(lattice_.moments(), n + 1);
        window_.du2 += s.du2, window_.u2 += s.u2, window_.dp2 += s.dp2, window_.p2 += s.p2;
        ++window_samples_;
      },
      1, first_s - 1);
}

void TaylorGreenErrorProbe::sample(const sim::ProbeContext& c, std::span<double> values) {
  const Sums s = sums(*c.moments, c.step);
  values[0] = std::sqrt(s.du2 / s.u2);
  values[1] = std::sqrt(s.dp2 / s.p2);
  const bool complete = c.step == steps_ && window_samples_ == steps_ - (3 * steps_ + 3) / 4 + 1;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  values[2] = complete ? std::sqrt(window_.du2 / window_.u2) : nan;
  values[3] = complete ? std::sqrt(window_.dp2 / window_.p2) : nan;
}

}  // namespace erythro::vv
