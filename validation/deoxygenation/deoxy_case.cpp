#include "deoxy_case.hpp"

#include <cmath>
#include <cstdio>

#include "common/case_support.hpp"

namespace erythro::deoxy {

const Result& Runner::at(double M, double beta) {
  const auto key = std::make_pair(M, beta);
  auto it = memo.find(key);
  if (it == memo.end()) {
    Setup s = base;
    s.hb.M = M;
    s.D_out = beta * base.D_out;
    it = memo.emplace(key, run(s)).first;
    ++runs;
  }
  return it->second;
}

namespace {

double norm_of(const std::vector<double>& r, vv::MisfitNorm norm) {
  double acc = 0.0;
  for (double v : r) acc = norm == vv::MisfitNorm::max_abs ? std::max(acc, std::abs(v)) : acc + v * v;
  return norm == vv::MisfitNorm::max_abs ? acc : std::sqrt(acc / static_cast<double>(r.size()));
}

}  // namespace

Fit fit_log(Runner& run, const vv::Curve& ref, const std::string& name,
            const std::function<std::pair<double, double>(double)>& point, double lo, double hi, double tol,
            vv::MisfitNorm norm, double fd_step) {
  vv::Stopwatch clock;
  const int runs0 = run.runs;
  const vv::CurveModel model = [&](const std::vector<double>& p) {
    const auto [M, beta] = point(p[0]);
    return run.at(M, beta).S;
  };
  vv::CalibrationOptions opt;
  opt.norm = norm;
  opt.x_tolerance = tol / (hi - lo);
  opt.fd_relative_step = fd_step / (hi - lo);
  Fit f;
  f.r = vv::calibrate_1d(model, ref, {name, lo, hi, 0.5 * (lo + hi)}, opt);
  f.value = std::exp(f.r.params[0]);
  // Is the fit a minimum? The norm at x ∓ δ from r + J δ (δ = fd_step).
  const auto r0 = vv::residuals(model(f.r.params), ref);
  std::vector<double> rm(r0.size()), rp(r0.size());
  for (std::size_t k = 0; k < r0.size(); ++k) {
    rm[k] = r0[k] - f.r.jacobian[k][0] * fd_step;
    rp[k] = r0[k] + f.r.jacobian[k][0] * fd_step;
  }
  f.norm_minus = norm_of(rm, norm);
  f.norm_plus = norm_of(rp, norm);
  f.runs = run.runs - runs0;
  f.wall_s = clock.seconds();
  return f;
}

std::string fmt(const char* format, double value) {
  char b[96];
  std::snprintf(b, sizeof b, format, value);
  return b;
}

io::Series curve_series(const std::string& name, const std::string& title, const vv::Curve& reference,
                        const vv::Curve& simulated) {
  io::Series s;
  s.name = name;
  s.title = title;
  s.xlabel = "t (s)";
  s.ylabel = "S";
  s.x = reference.t;
  s.y_reference = reference.y;
  for (double t : reference.t) s.y.push_back(vv::interpolate(simulated, t));
  return s;
}

}  // namespace erythro::deoxy
