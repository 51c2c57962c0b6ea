#include "common/calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace erythro::vv {

double interpolate(const Curve& c, double t) {
  const std::size_t n = c.t.size();
  if (n == 0 || c.y.size() != n) throw std::invalid_argument("interpolate: empty curve or t/y sizes differ");
  const double slack = 1e-12 * std::max(1.0, std::abs(c.t.back() - c.t.front()));
  if (t < c.t.front() - slack || t > c.t.back() + slack)
    throw std::invalid_argument("interpolate: t = " + std::to_string(t) + " outside the simulated curve [" +
                                std::to_string(c.t.front()) + ", " + std::to_string(c.t.back()) + "]");
  if (n == 1) return c.y[0];
  auto it = std::upper_bound(c.t.begin(), c.t.end(), t);
  std::size_t k = static_cast<std::size_t>(it - c.t.begin());
  k = std::clamp<std::size_t>(k, 1, n - 1);
  const double t0 = c.t[k - 1], t1 = c.t[k];
  const double s = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
  return c.y[k - 1] + s * (c.y[k] - c.y[k - 1]);
}

std::vector<double> residuals(const Curve& simulated, const Curve& reference) {
  if (reference.t.size() != reference.y.size() || reference.t.empty())
    throw std::invalid_argument("residuals: empty reference or t/y sizes differ");
  std::vector<double> r(reference.t.size());
  for (std::size_t k = 0; k < r.size(); ++k) r[k] = interpolate(simulated, reference.t[k]) - reference.y[k];
  return r;
}

static Misfit misfit_of(const std::vector<double>& r) {
  Misfit m;
  double ss = 0.0;
  for (double v : r) {
    m.max_abs = std::max(m.max_abs, std::abs(v));
    ss += v * v;
  }
  m.rms = std::sqrt(ss / static_cast<double>(r.size()));
  return m;
}

Misfit curve_misfit(const Curve& simulated, const Curve& reference) {
  return misfit_of(residuals(simulated, reference));
}

double CalibrationResult::width(std::size_t i, double delta) const {
  const double s = sensitivity_rms.at(i);
  return s > 0.0 ? delta / s : std::numeric_limits<double>::infinity();
}

double brent_minimize(const std::function<double(double)>& f, double a, double b, double tol, int max_evaluations,
                      int* evaluations, bool* converged) {
  // Brent (1973), "Algorithms for minimization without derivatives", ch. 5 (localmin).
  const double golden = 0.5 * (3.0 - std::sqrt(5.0));
  const double eps = std::sqrt(std::numeric_limits<double>::epsilon());
  if (!(a < b)) throw std::invalid_argument("brent_minimize: need lower < upper");
  double x = a + golden * (b - a), w = x, v = x;
  double fx = f(x), fw = fx, fv = fx;
  int evals = 1;
  double d = 0.0, e = 0.0;
  bool done = false;
  while (evals < max_evaluations) {
    const double m = 0.5 * (a + b);
    const double tol1 = eps * std::abs(x) + tol / 3.0, tol2 = 2.0 * tol1;
    if (std::abs(x - m) <= tol2 - 0.5 * (b - a)) {
      done = true;
      break;
    }
    bool parabolic = false;
    if (std::abs(e) > tol1) {  // try a parabola through x, w, v
      double r = (x - w) * (fx - fv), q = (x - v) * (fx - fw), p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::abs(q);
      const double e_old = e;
      e = d;
      if (std::abs(p) < std::abs(0.5 * q * e_old) && p > q * (a - x) && p < q * (b - x)) {
        d = p / q;
        const double u = x + d;
        if (u - a < tol2 || b - u < tol2) d = (x < m) ? tol1 : -tol1;
        parabolic = true;
      }
    }
    if (!parabolic) {  // golden-section step into the larger part
      e = (x < m) ? b - x : a - x;
      d = golden * e;
    }
    const double u = (std::abs(d) >= tol1) ? x + d : x + (d > 0 ? tol1 : -tol1);
    const double fu = f(u);
    ++evals;
    if (fu <= fx) {
      if (u < x) b = x; else a = x;
      v = w; fv = fw; w = x; fw = fx; x = u; fx = fu;
    } else {
      if (u < x) a = u; else b = u;
      if (fu <= fw || w == x) {
        v = w; fv = fw; w = u; fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u; fv = fu;
      }
    }
  }
  if (evaluations) *evaluations += evals;
  if (converged) *converged = done;
  return x;
}

namespace {

void check_bounds(const std::vector<ParameterBound>& bounds) {
  if (bounds.empty()) throw std::invalid_argument("calibrate: no parameters");
  for (const auto& b : bounds)
    if (!(b.lower < b.upper))
      throw std::invalid_argument("calibrate: parameter '" + b.name + "' needs lower < upper");
}

double objective_of(const Misfit& m, MisfitNorm norm) { return norm == MisfitNorm::max_abs ? m.max_abs : m.rms; }

// Fills misfit, objective, at_bound and the central-difference Jacobian at the optimum.
// The Jacobian's points: central differences, one-sided into the box at a bound.
void jacobian_points(const CalibrationResult& res, const std::vector<ParameterBound>& bounds,
                     const CalibrationOptions& opt, std::vector<std::vector<double>>& lo,
                     std::vector<std::vector<double>>& hi) {
  for (std::size_t i = 0; i < bounds.size(); ++i) {
    const double step = opt.fd_relative_step * (bounds[i].upper - bounds[i].lower);
    lo.push_back(res.params);
    hi.push_back(res.params);
    hi.back()[i] = std::min(res.params[i] + step, bounds[i].upper);
    lo.back()[i] = std::max(res.params[i] - step, bounds[i].lower);
  }
}

// Sensitivities and the Gauss–Newton standard error from res.jacobian and the residuals r0.
void statistics(CalibrationResult& res, const std::vector<double>& r0, std::size_t n);

void finish(CalibrationResult& res, const CurveModel& model, const Curve& reference,
            const std::vector<ParameterBound>& bounds, const CalibrationOptions& opt) {
  const std::size_t n = bounds.size(), K = reference.t.size();
  std::vector<std::vector<double>> los, his;
  jacobian_points(res, bounds, opt, los, his);
  if (opt.prefetch) {
    std::vector<std::vector<double>> points{res.params};
    for (std::size_t i = 0; i < n; ++i) {
      points.push_back(his[i]);
      points.push_back(los[i]);
    }
    opt.prefetch(points);
  }
  const auto r0 = residuals(model(res.params), reference);
  res.sensitivity_evaluations = 1;
  res.misfit = misfit_of(r0);
  res.objective = objective_of(res.misfit, opt.norm);
  res.names.clear();
  res.at_bound.assign(n, false);
  res.jacobian.assign(K, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) {
    const double range = bounds[i].upper - bounds[i].lower, tol = opt.x_tolerance * range;
    res.names.push_back(bounds[i].name);
    res.at_bound[i] = res.params[i] - bounds[i].lower <= 2.0 * tol || bounds[i].upper - res.params[i] <= 2.0 * tol;
    // central difference, one-sided into the box at a bound
    const std::vector<double>& lo = los[i];
    const std::vector<double>& hi = his[i];
    const auto rh = residuals(model(hi), reference), rl = residuals(model(lo), reference);
    res.sensitivity_evaluations += 2;
    for (std::size_t k = 0; k < K; ++k) res.jacobian[k][i] = (rh[k] - rl[k]) / (hi[i] - lo[i]);
  }
  statistics(res, r0, n);
}

void statistics(CalibrationResult& res, const std::vector<double>& r0, std::size_t n) {
  const std::size_t K = r0.size();
  res.sensitivity_rms.assign(n, 0.0);
  res.sensitivity_max.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double ss = 0.0;
    for (std::size_t k = 0; k < K; ++k) {
      ss += res.jacobian[k][i] * res.jacobian[k][i];
      res.sensitivity_max[i] = std::max(res.sensitivity_max[i], std::abs(res.jacobian[k][i]));
    }
    res.sensitivity_rms[i] = std::sqrt(ss / static_cast<double>(K));
  }
  // Gauss–Newton standard error: the diagonal of s² (JᵀJ)⁻¹, s² = |r0|²/(K − n). With
  // J = QR (column-pivoted Householder), (JᵀJ)⁻¹ = P R⁻¹ R⁻ᵀ Pᵀ; a rank-deficient J means
  // the parameters are not identifiable (errors stay infinite).
  res.gn_standard_error.assign(n, std::numeric_limits<double>::infinity());
  if (K <= n) return;
  Eigen::MatrixXd J(static_cast<Eigen::Index>(K), static_cast<Eigen::Index>(n));
  for (std::size_t k = 0; k < K; ++k)
    for (std::size_t i = 0; i < n; ++i) J(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)) = res.jacobian[k][i];
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(J);
  if (qr.rank() < static_cast<Eigen::Index>(n)) return;
  const Eigen::MatrixXd R = qr.matrixR().topLeftCorner(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n))
                                .triangularView<Eigen::Upper>();
  const Eigen::MatrixXd R_inv =
      R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(R.rows(), R.cols()));
  const Eigen::MatrixXd covariance = qr.colsPermutation() * (R_inv * R_inv.transpose()) *
                                     qr.colsPermutation().transpose();
  const double s2 = Eigen::Map<const Eigen::VectorXd>(r0.data(), static_cast<Eigen::Index>(K)).squaredNorm() /
                    static_cast<double>(K - n);
  for (std::size_t i = 0; i < n; ++i)
    res.gn_standard_error[i] = std::sqrt(s2 * covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)));
}

}  // namespace

CalibrationResult calibrate_1d(const CurveModel& model, const Curve& reference, const ParameterBound& bound,
                               const CalibrationOptions& options) {
  check_bounds({bound});
  CalibrationResult res;
  auto f = [&](double x) { return objective_of(curve_misfit(model({x}), reference), options.norm); };
  const double tol = options.x_tolerance * (bound.upper - bound.lower);
  const double x = brent_minimize(f, bound.lower, bound.upper, tol, options.max_evaluations, &res.evaluations,
                                  &res.converged);
  res.params = {x};
  finish(res, model, reference, {bound}, options);
  return res;
}

namespace {

// argmin over d ∈ [lo, hi] of the linearised norm of r + J d.
double linearised_step(const std::vector<double>& r, const std::vector<double>& J, MisfitNorm norm, double lo,
                       double hi) {
  if (norm == MisfitNorm::rms) {
    double jr = 0.0, jj = 0.0;
    for (std::size_t k = 0; k < r.size(); ++k) {
      jr += J[k] * r[k];
      jj += J[k] * J[k];
    }
    return jj > 0.0 ? std::clamp(-jr / jj, lo, hi) : 0.0;
  }
  // max_k |r_k + J_k d| is convex and piecewise linear: golden section to round-off
  const auto f = [&](double d) {
    double m = 0.0;
    for (std::size_t k = 0; k < r.size(); ++k) m = std::max(m, std::abs(r[k] + J[k] * d));
    return m;
  };
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, b = hi, c = b - g * (b - a), e = a + g * (b - a), fc = f(c), fe = f(e);
  for (int it = 0; it < 200 && b - a > 1e-15 * std::max(1.0, std::abs(a) + std::abs(b)); ++it) {
    if (fc <= fe) {
      b = e;
      e = c;
      fe = fc;
      c = b - g * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = e;
      fc = fe;
      e = a + g * (b - a);
      fe = f(e);
    }
  }
  return 0.5 * (a + b);
}

}  // namespace

CalibrationResult refine_1d(const CurveModel& model, const Curve& reference, const ParameterBound& bound, double x0,
                            const CalibrationOptions& options) {
  check_bounds({bound});
  const double range = bound.upper - bound.lower, tol = options.x_tolerance * range;
  const double delta = options.fd_relative_step * range;
  const std::size_t K = reference.t.size();
  CalibrationResult res;
  res.names = {bound.name};
  auto run = [&](double x) {
    ++res.evaluations;
    return residuals(model({x}), reference);
  };
  double x = std::clamp(x0, bound.lower, bound.upper);
  std::vector<double> J(K), r;  // J at the centre xc; r at x once x has been run
  double xc = 0.0;
  bool have_r = false;
  // J by central differences around c (one-sided into the bracket at an edge); without a
  // run at c, r(c) is taken as the mean of the pair (O(δ²)) for the first step only.
  auto differences = [&](double c) {
    const double lo = std::max(c - delta, bound.lower), hi = std::min(c + delta, bound.upper);
    if (options.prefetch) options.prefetch({{lo}, {hi}});
    const auto rl = run(lo), rh = run(hi);
    for (std::size_t k = 0; k < K; ++k) J[k] = (rh[k] - rl[k]) / (hi - lo);
    xc = c;
    if (!have_r) {
      r.resize(K);
      for (std::size_t k = 0; k < K; ++k) r[k] = rl[k] + (c - lo) * J[k];  // linear through the pair at c
    }
  };
  differences(x);
  while (res.evaluations < options.max_evaluations) {
    const double step = linearised_step(r, J, options.norm, bound.lower - x, bound.upper - x);
    if (have_r && std::abs(step) <= tol) {
      res.converged = true;
      break;
    }
    x += step;
    if (options.prefetch) options.prefetch({{x}});  // (one point: lets a caller start work that follows it)
    r = run(x);
    have_r = true;
    if (std::abs(x - xc) > 0.5 * delta) differences(x);  // the Jacobian follows a larger move
  }
  res.params = {x};
  res.sensitivity_evaluations = 0;
  res.misfit = misfit_of(r);
  res.objective = objective_of(res.misfit, options.norm);
  res.at_bound = {x - bound.lower <= 2.0 * tol || bound.upper - x <= 2.0 * tol};
  res.jacobian.assign(K, std::vector<double>(1, 0.0));
  for (std::size_t k = 0; k < K; ++k) res.jacobian[k][0] = J[k];
  statistics(res, r, 1);
  return res;
}

CalibrationResult calibrate(const CurveModel& model, const Curve& reference, const std::vector<ParameterBound>& bounds,
                            const CalibrationOptions& options) {
  check_bounds(bounds);
  const std::size_t n = bounds.size();
  CalibrationResult res;
  auto clamp_in = [&](std::vector<double> p) {
    for (std::size_t i = 0; i < n; ++i) p[i] = std::clamp(p[i], bounds[i].lower, bounds[i].upper);
    return p;
  };
  auto f = [&](const std::vector<double>& p) {
    ++res.evaluations;
    return objective_of(curve_misfit(model(p), reference), options.norm);
  };
  // Nelder–Mead (Lagarias et al. 1998 coefficients: reflect 1, expand 2, contract ½, shrink ½).
  std::vector<std::vector<double>> x(n + 1);
  std::vector<double> fx(n + 1);
  std::vector<double> start(n);
  for (std::size_t i = 0; i < n; ++i) start[i] = bounds[i].initial;
  x[0] = clamp_in(start);
  for (std::size_t i = 0; i < n; ++i) {
    x[i + 1] = x[0];
    const double step = 0.1 * (bounds[i].upper - bounds[i].lower);
    x[i + 1][i] = x[0][i] + step <= bounds[i].upper ? x[0][i] + step : x[0][i] - step;
  }
  if (options.prefetch) options.prefetch(x);
  for (std::size_t j = 0; j <= n; ++j) fx[j] = f(x[j]);
  while (res.evaluations < options.max_evaluations) {
    std::vector<std::size_t> order(n + 1);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return fx[a] < fx[b]; });
    std::vector<std::vector<double>> xs(n + 1);
    std::vector<double> fs(n + 1);
    for (std::size_t j = 0; j <= n; ++j) {
      xs[j] = x[order[j]];
      fs[j] = fx[order[j]];
    }
    x = xs;
    fx = fs;
    // stop: simplex smaller than the tolerance in every parameter (relative to range)
    double size = 0.0;
    for (std::size_t j = 1; j <= n; ++j)
      for (std::size_t i = 0; i < n; ++i)
        size = std::max(size, std::abs(x[j][i] - x[0][i]) / (bounds[i].upper - bounds[i].lower));
    if (size <= options.x_tolerance) {
      res.converged = true;
      break;
    }
    std::vector<double> c(n, 0.0);  // centroid of all but the worst
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) c[i] += x[j][i] / static_cast<double>(n);
    auto along = [&](double t) {
      std::vector<double> p(n);
      for (std::size_t i = 0; i < n; ++i) p[i] = c[i] + t * (x[n][i] - c[i]);
      return clamp_in(p);
    };
    const auto xr = along(-1.0);
    const double fr = f(xr);
    if (fr < fx[0]) {
      const auto xe = along(-2.0);
      const double fe = f(xe);
      if (fe < fr) { x[n] = xe; fx[n] = fe; } else { x[n] = xr; fx[n] = fr; }
    } else if (fr < fx[n - 1]) {
      x[n] = xr; fx[n] = fr;
    } else {
      const bool outside = fr < fx[n];
      const auto xc = along(outside ? -0.5 : 0.5);
      const double fc = f(xc);
      if (fc < (outside ? fr : fx[n])) {
        x[n] = xc; fx[n] = fc;
      } else {  // shrink towards the best
        for (std::size_t j = 1; j <= n; ++j)
          for (std::size_t i = 0; i < n; ++i) x[j][i] = x[0][i] + 0.5 * (x[j][i] - x[0][i]);
        if (options.prefetch) options.prefetch({x.begin() + 1, x.end()});
        for (std::size_t j = 1; j <= n; ++j) fx[j] = f(x[j]);
      }
    }
  }
  const auto best = std::min_element(fx.begin(), fx.end()) - fx.begin();
  res.params = x[static_cast<std::size_t>(best)];
  finish(res, model, reference, bounds, options);
  return res;
}

}  // namespace erythro::vv
