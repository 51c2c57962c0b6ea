#include "deoxy_case.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/case_support.hpp"
#include "common/error.hpp"

namespace erythro::deoxy {

// ------------------------------------------------------------------ concurrent runs

Slots& Slots::instance() {
  static Slots slots(std::max(1, omp_get_max_threads()));
  return slots;
}

void Slots::acquire(int priority) {
  std::unique_lock lock(m_);
  const auto me = waiting_.insert(priority);
  cv_.wait(lock, [&] { return free_ > 0 && *waiting_.rbegin() == priority; });
  waiting_.erase(me);
  --free_;
  cv_.notify_all();  // another free slot may now go to the next waiter
}

void Slots::release() {
  {
    std::lock_guard lock(m_);
    ++free_;
  }
  cv_.notify_all();
}

namespace {
std::atomic<long> run_counter{0};
}  // namespace

Runner::Runner(Setup setup, std::string case_name, int priority)
    : base_(std::move(setup)), case_name_(std::move(case_name)), priority_(priority) {}

Runner::~Runner() {
  for (auto& f : background_)
    if (f.valid()) f.wait();
}

int Runner::runs() const {
  std::lock_guard lock(m_);
  return runs_;
}

std::shared_ptr<std::promise<Result>> Runner::claim(std::pair<double, double> key, std::shared_future<Result>& result) {
  std::lock_guard lock(m_);
  auto it = memo_.find(key);
  if (it != memo_.end()) {
    result = it->second;
    return nullptr;
  }
  auto promise = std::make_shared<std::promise<Result>>();
  result = promise->get_future().share();
  memo_.emplace(key, result);
  ++runs_;
  return promise;
}

void Runner::compute(std::pair<double, double> key, std::promise<Result>& promise, int priority) {
  Setup s = base_;
  s.hb.M = key.first;
  s.D_out = key.second * base_.D_out;
  Slots& slots = Slots::instance();
  slots.acquire(priority >= 0 ? priority : priority_);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);  // one run per worker (the small grids do not thread anyway)
  try {
    const std::string label = fmt("h%.2f_", s.h_um) + std::to_string(run_counter++);
    promise.set_value(run(s, case_name_, label));
  } catch (...) {
    promise.set_exception(std::current_exception());
  }
  omp_set_num_threads(threads);
  slots.release();
}

const Result& Runner::at(double M, double beta, int priority) {
  const auto key = std::make_pair(M, beta);
  std::shared_future<Result> result;
  if (auto promise = claim(key, result)) compute(key, *promise, priority);
  return result.get();  // the memo keeps the shared state (and so the reference) alive
}

void Runner::prefetch(const std::vector<std::pair<double, double>>& points, int priority) {
  for (const auto& p : points) {
    std::shared_future<Result> result;
    auto promise = claim(p, result);  // claimed here, so runs() counts it from now on
    if (!promise) continue;
    auto f = std::async(std::launch::async, [this, p, promise, priority] { compute(p, *promise, priority); });
    std::lock_guard lock(m_);
    background_.push_back(std::move(f));
  }
}

// ------------------------------------------------------------------ fits

namespace {

double norm_of(const std::vector<double>& r, vv::MisfitNorm norm) {
  double acc = 0.0;
  for (double v : r) acc = norm == vv::MisfitNorm::max_abs ? std::max(acc, std::abs(v)) : acc + v * v;
  return norm == vv::MisfitNorm::max_abs ? acc : std::sqrt(acc / static_cast<double>(r.size()));
}

struct FitContext {
  vv::CurveModel model;
  vv::CalibrationOptions opt;
};

FitContext context(Runner& run, const PointOf& point, double lo, double hi, double tol, vv::MisfitNorm norm,
                   double fd_step, int priority) {
  FitContext c;
  c.model = [&run, point, priority](const std::vector<double>& p) {
    const auto [M, beta] = point(p[0]);
    return run.at(M, beta, priority).S;
  };
  c.opt.norm = norm;
  c.opt.x_tolerance = tol / (hi - lo);
  c.opt.fd_relative_step = fd_step / (hi - lo);
  c.opt.prefetch = [&run, point, priority](const std::vector<std::vector<double>>& xs) {
    std::vector<std::pair<double, double>> points;
    for (const auto& x : xs) points.push_back(point(x[0]));
    run.prefetch(points, priority);
  };
  return c;
}

// Is the fit a minimum? The norm at x ∓ δ from r + J δ (δ = fd_step).
void linearised_sides(Fit& f, const FitContext& c, const vv::Curve& ref, vv::MisfitNorm norm, double fd_step) {
  const auto r0 = vv::residuals(c.model(f.r.params), ref);
  std::vector<double> rm(r0.size()), rp(r0.size());
  for (std::size_t k = 0; k < r0.size(); ++k) {
    rm[k] = r0[k] - f.r.jacobian[k][0] * fd_step;
    rp[k] = r0[k] + f.r.jacobian[k][0] * fd_step;
  }
  f.norm_minus = norm_of(rm, norm);
  f.norm_plus = norm_of(rp, norm);
}

}  // namespace

Fit fit_log(Runner& run, const vv::Curve& ref, const std::string& name, const PointOf& point, double lo, double hi,
            double tol, vv::MisfitNorm norm, double fd_step, int priority) {
  vv::Stopwatch clock;
  const FitContext c = context(run, point, lo, hi, tol, norm, fd_step, priority);
  Fit f;
  f.r = vv::calibrate_1d(c.model, ref, {name, lo, hi, 0.5 * (lo + hi)}, c.opt);
  f.value = std::exp(f.r.params[0]);
  linearised_sides(f, c, ref, norm, fd_step);
  f.wall_s = clock.seconds();
  return f;
}

std::pair<double, double> warm_pair(double x0, double fd_step) {
  // as fit_log_warm → context → refine_1d compute them: δ = (fd_step / range) range on the
  // bracket x0 ± kWarmHalfBracket
  const double lo = x0 - kWarmHalfBracket, hi = x0 + kWarmHalfBracket;
  const double delta = fd_step / (hi - lo) * (hi - lo);
  return {std::max(x0 - delta, lo), std::min(x0 + delta, hi)};
}

Fit fit_log_warm(Runner& run, const vv::Curve& ref, const std::string& name, const PointOf& point, double x0,
                 double tol, vv::MisfitNorm norm, double fd_step, int priority,
                 const std::function<void(double)>& on_iterate) {
  vv::Stopwatch clock;
  const double lo = x0 - kWarmHalfBracket, hi = x0 + kWarmHalfBracket;
  FitContext c = context(run, point, lo, hi, tol, norm, fd_step, priority);
  if (on_iterate) {
    const auto pair = c.opt.prefetch;
    c.opt.prefetch = [pair, on_iterate](const std::vector<std::vector<double>>& xs) {
      if (xs.size() == 1) on_iterate(xs[0][0]);  // an iterate (refine_1d prefetches it alone)
      pair(xs);
    };
  }
  Fit f;
  f.r = vv::refine_1d(c.model, ref, {name, lo, hi, x0}, x0, c.opt);
  f.value = std::exp(f.r.params[0]);
  linearised_sides(f, c, ref, norm, fd_step);
  f.wall_s = clock.seconds();
  return f;
}

// ------------------------------------------------------------------ stage 1

std::vector<std::unique_ptr<Runner>> stage1_runners(const vv::Curve& planar, const std::string& case_name) {
  std::vector<std::unique_ptr<Runner>> runners;
  for (std::size_t i = 0; i < kLevels.size(); ++i)
    runners.push_back(std::make_unique<Runner>(case_setup(kLevels[i], planar.t.back()), case_name, level_priority(i)));
  return runners;
}

std::vector<StageOneLevel> stage1_fits(std::vector<std::unique_ptr<Runner>>& runners, const vv::Curve& planar,
                                       const std::function<void(double)>& finest_iterate) {
  const PointOf point = [](double x) { return std::make_pair(std::exp(x), 1.0); };
  std::vector<StageOneLevel> levels(kLevels.size());
  auto level = [&](std::size_t i, const std::function<Fit(Runner&)>& fit) {
    vv::Stopwatch clock;
    StageOneLevel& L = levels[i];
    L.h = kLevels[i];
    L.dt = diffusive_dt(L.h, kDtAt0p2);
    L.planar = fit(*runners[i]);
    L.wall_s = clock.seconds();
    std::printf("h = %.2f um planar: M = %.6f (bound %d, %d evals + %d), max %.5f rms %.5f; %.0f s\n", L.h,
                L.planar.value, static_cast<int>(L.planar.r.at_bound[0]), L.planar.r.evaluations,
                L.planar.r.sensitivity_evaluations, L.planar.r.misfit.max_abs, L.planar.r.misfit.rms, L.wall_s);
    std::fflush(stdout);
  };
  // The coarsest level's free fit (tolerance 0.01) runs beside the chain 0.3 (free, 1e-3) → 0.2 →
  // 0.15 (each warm from the previous level's fit, 1e-3).
  auto coarsest = std::async(std::launch::async, [&] {
    level(0, [&](Runner& r) {
      return fit_log(r, planar, "lnM", point, kLnMLower, kLnMUpper, 0.01, vv::MisfitNorm::rms, kFdLnM);
    });
  });
  level(1, [&](Runner& r) {
    return fit_log(r, planar, "lnM", point, kLnMLower, kLnMUpper, 1e-3, vv::MisfitNorm::rms, kFdLnM);
  });
  for (std::size_t i = 2; i < kLevels.size(); ++i) {
    const double x0 = levels[i - 1].planar.r.params[0];
    // on an iterate (almost always the fit): the next level's pair starts, below this level's runs
    std::function<void(double)> on_iterate = [&, i](double x) {
      if (i + 1 < kLevels.size()) {
        const auto [a, b] = warm_pair(x, kFdLnM);
        runners[i + 1]->prefetch({point(a), point(b)}, level_priority(i) - 5);
      } else if (finest_iterate) {
        finest_iterate(std::exp(x));
      }
    };
    level(i, [&](Runner& r) {
      return fit_log_warm(r, planar, "lnM", point, x0, 1e-3, vv::MisfitNorm::rms, kFdLnM, -1, on_iterate);
    });
  }
  coarsest.get();
  return levels;
}

std::string stage1_path() { return io::ResultRecord::results_dir() + "/deoxygenation_stage1.tsv"; }

void write_stage1(const std::vector<StageOneLevel>& levels, double wall_s) {
  std::ofstream out(stage1_path());
  if (!out) throw OutputError("cannot write " + stage1_path());
  out << "# stage 1 of the deoxygenation calibration (validation.deoxygenation): M against the planar section\n";
  out << "# wall_s " << fmt("%.17g", wall_s) << "\n";
  out << "# h dt lnM M max rms objective at_bound evaluations sensitivity_evaluations norm_minus norm_plus wall_s\n";
  for (const auto& L : levels) {
    const auto& r = L.planar.r;
    for (double v : {L.h, L.dt, r.params[0], L.planar.value, r.misfit.max_abs, r.misfit.rms, r.objective,
                     r.at_bound[0] ? 1.0 : 0.0, static_cast<double>(r.evaluations),
                     static_cast<double>(r.sensitivity_evaluations), L.planar.norm_minus, L.planar.norm_plus,
                     L.wall_s})
      out << fmt("%.17g", v) << ' ';
    out << '\n';
  }
}

std::vector<StageOneLevel> read_stage1(double* wall_s) {
  std::ifstream in(stage1_path());
  std::vector<StageOneLevel> levels;
  if (!in) return levels;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# wall_s ", 0) == 0 && wall_s) *wall_s = std::stod(line.substr(9));
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::vector<double> v;
    for (double x; ss >> x;) v.push_back(x);
    if (v.size() != 13) throw InputError(stage1_path() + ": malformed row '" + line + "'");
    StageOneLevel L;
    L.h = v[0];
    L.dt = v[1];
    L.planar.r.params = {v[2]};
    L.planar.value = v[3];
    L.planar.r.misfit = {v[4], v[5]};
    L.planar.r.objective = v[6];
    L.planar.r.at_bound = {v[7] != 0.0};
    L.planar.r.evaluations = static_cast<int>(v[8]);
    L.planar.r.sensitivity_evaluations = static_cast<int>(v[9]);
    L.planar.norm_minus = v[10];
    L.planar.norm_plus = v[11];
    L.wall_s = v[12];
    levels.push_back(L);
  }
  return levels;
}

// ------------------------------------------------------------------ records

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
