// Case verification.galilean_symmetry (issue 3 item 5).
//
// Requirement: (a) a uniform flow in a periodic box stays uniform to round-off;
// (b) mirror-symmetric set-ups stay mirror-symmetric to round-off; (c) the decay
// rate of a shear wave carried by a uniform flow u0 differs from the one at rest by
// the D2Q9 Galilean error −3 (u0·k̂)² (relative), which scales as u0².
// Reference: (a), (b) the symmetries of the D2Q9 scheme (uniform states are exact
// fixed points; the velocity set is invariant under x → −x and y → −y); (c) the
// Chapman–Enskog stress of the second-order equilibrium on D2Q9, whose third moment
// lacks ρu_αu_βu_γ: σ_αβ = ρν(∂_αu_β + ∂_βu_α) − (τ − ½)∂_γ(ρu_αu_βu_γ) (Krüger et al.
// 2017, The Lattice Boltzmann Method, §4.1; Dellar 2003, J Comput Phys 190:351). For
// u = (a, v(x)) the extra term is −(τ − ½)a²ρ ∂_x v, i.e. ν_eff = ν(1 − a²/c_s²).
//
// Runs: (a) verification/fluid/periodic_box.toml with initial.type = "uniform"; (b) the
// mirror-symmetric channel (channel.toml with a steady [body_force]) and box
// (periodic_box.toml), their starts set on the fluid before the run, fields every 100
// steps; (c) periodic_box.toml at N × 4 with the carrier flow as initial.type =
// "uniform", the shear wave added to the start before the run (with its non-equilibrium
// part, fluid/initial_state.hpp), fields at t_d/10 and t_d. Fields are read in lattice
// units (a sim::FieldsRecorder), bit for bit as computed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

#include "common/case_support.hpp"
#include "common/scene_case.hpp"
#include "fluid/initial_state.hpp"
#include "fluid_scenes.hpp"
#include "simulation/fields_recorder.hpp"

using namespace erythro;

namespace {
constexpr double kTau = 0.8;
constexpr double kNu = (kTau - 0.5) / 3.0;
constexpr const char* kCase = "verification.galilean_symmetry";

const vv::SceneFile& box_scene() {
  static const vv::SceneFile f("verification/fluid/periodic_box.toml");
  return f;
}
const vv::SceneFile& channel_scene() {
  static const vv::SceneFile f("verification/fluid/channel.toml");
  return f;
}

// The scene's common overrides: grid, collision, steps, τ.
std::vector<std::string> base(const vv::SceneFile& file, fluid::CollisionModel model, int nx, int ny, long steps) {
  std::vector<std::string> o = {vv::set_grid(nx, ny), vv::set_collision(model), vv::set("run.steps", steps)};
  o.push_back(vv::set_tau(file, o, kTau));
  return o;
}

// Runs the scene and returns the recorder of its fields.
std::pair<vv::CaseRun, std::unique_ptr<sim::FieldsRecorder>> run(const vv::SceneFile& file,
                                                                 const std::vector<std::string>& o,
                                                                 const std::string& label,
                                                                 std::function<void(sim::Simulation&)> configure = {}) {
  auto fields = std::make_unique<sim::FieldsRecorder>();
  vv::CaseRunOptions options;
  options.configure = std::move(configure);
  options.observers.push_back(fields.get());
  vv::CaseRun r = vv::run_case_scene(file.scene(o), kCase, label, options);
  if (!r.ok()) throw std::runtime_error(label + ": " + r.summary.diagnosis);
  return {std::move(r), std::move(fields)};
}

// (a) Uniform flow: max |u − u0| / |u0| and the spread max − min over nodes.
struct UniformResult {
  double deviation = 0, spread = 0, rho_deviation = 0;
  std::string scene_text;
};

UniformResult run_uniform(fluid::CollisionModel model, double ux0, double uy0, long steps) {
  const vv::SceneFile& file = box_scene();
  std::vector<std::string> o = base(file, model, 32, 32, steps);
  o.push_back(vv::set("initial.type", "\"uniform\""));
  o.push_back(vv::set("limits.max_mach", 0.3));  // |u0| = 0.11: Ma = 0.19
  o.push_back(vv::set_initial_velocity(file, o, {ux0, uy0}));
  const auto [r, fields] = run(file, o, std::string(fluid::to_string(model)) + "_uniform_" + std::to_string(steps));
  ux0 = r.setup.initial_velocity[0], uy0 = r.setup.initial_velocity[1];  // the same bits (fluid_scenes.hpp)
  const fluid::Moments& m = fields->last().moments;
  UniformResult u;
  const auto [xlo, xhi] = std::minmax_element(m.ux.begin(), m.ux.end());
  const auto [ylo, yhi] = std::minmax_element(m.uy.begin(), m.uy.end());
  for (std::size_t n = 0; n < m.ux.size(); ++n) {
    u.deviation = std::max(u.deviation, std::hypot(m.ux[n] - ux0, m.uy[n] - uy0) / std::hypot(ux0, uy0));
    u.rho_deviation = std::max(u.rho_deviation, std::abs(m.rho[n] - 1.0));
  }
  u.spread = std::max(*xhi - *xlo, *yhi - *ylo);
  u.scene_text = r.file.scene_text();
  return u;
}

// (b) Mirror symmetry. Largest |u(x) ∓ u(mirror x)| over nodes, relative to max|u| at
// that time, and largest |ρ(x) − ρ(mirror x)|, over the run (sampled every 100 steps).
struct MirrorResult {
  double velocity_asymmetry = 0;   // max |u ∓ u_mirror| / max|u|
  double density_asymmetry = 0;    // max |ρ − ρ_mirror|
  double exact_zero_fraction = 0;  // nodes whose velocity is bitwise the mirror image, at the end
  std::string scene_text;
};

// Mirror about y (node j ↔ N − 1 − j: u_x even, u_y odd) or about x (node i ↔ N − 1 − i:
// u_x odd, u_y even), measured on the fields output every 100 steps.
enum class MirrorAxis { y, x };

MirrorResult measure_mirror(const sim::FieldsRecorder& fields, const Grid& g, MirrorAxis axis, io::Series* trace) {
  const int N = g.nx;
  const double sx = axis == MirrorAxis::x ? -1.0 : 1.0;  // sign of u_x under the mirror
  MirrorResult r;
  for (const sim::FieldsRecorder::Snapshot& frame : fields.snapshots()) {
    if (frame.step == 0) continue;  // the start; sampled from step 100 on
    const fluid::Moments& m = frame.moments;
    double umax = 0, asym = 0, drho = 0;
    long exact = 0;
    for (int j = 0; j < N; ++j) {
      for (int i = 0; i < N; ++i) {
        const auto n = g.index(i, j);
        const auto mirror = axis == MirrorAxis::y ? g.index(i, N - 1 - j) : g.index(N - 1 - i, j);
        umax = std::max(umax, std::hypot(m.ux[n], m.uy[n]));
        const double d = std::max({std::abs(m.ux[n] - sx * m.ux[mirror]), std::abs(m.uy[n] + sx * m.uy[mirror])});
        drho = std::max(drho, std::abs(m.rho[n] - m.rho[mirror]));
        asym = std::max(asym, d);
        if (d == 0.0) ++exact;
      }
    }
    r.velocity_asymmetry = std::max(r.velocity_asymmetry, asym / umax);
    r.density_asymmetry = std::max(r.density_asymmetry, drho);
    r.exact_zero_fraction = double(exact) / double(g.size());
    if (trace) {
      trace->x.push_back(double(frame.step));
      trace->y.push_back(asym / umax);
    }
  }
  return r;
}

// Mirror about the mid-plane y = N/2 of a channel: node j ↔ N − 1 − j; u_x even, u_y odd.
MirrorResult run_channel_mirror(fluid::CollisionModel model, long steps) {
  const int N = 32;
  const Grid g{N, N};
  const vv::SceneFile& file = channel_scene();
  std::vector<std::string> o = base(file, model, N, N, steps);
  o.push_back(vv::set("output.fields_interval_steps", 100L));
  o.push_back(vv::set_body_force(file, o, {1e-5, 0.0}));
  const auto [r, fields] = run(file, o, std::string(fluid::to_string(model)) + "_channel_mirror",
                               [&](sim::Simulation& simulation) {
                                 const double k = 2.0 * std::numbers::pi / N;
                                 std::vector<double> rho(g.size()), ux(g.size()), uy(g.size());
                                 for (int j = 0; j < N; ++j) {
                                   for (int i = 0; i < N; ++i) {
                                     const double x = i + 0.5, y = j + 0.5;
                                     const auto n = g.index(i, j);
                                     // Even/odd about y = N/2: cos(2π y/N) is even, sin(2π y/N) is odd.
                                     ux[n] = 0.02 * std::cos(k * x) * std::cos(k * y);
                                     uy[n] = 0.02 * std::sin(k * x) * std::sin(k * y);
                                     rho[n] = 1.0 + 0.001 * std::sin(k * x) * std::cos(k * y);
                                   }
                                 }
                                 simulation.fluid()->initialize(rho, ux, uy);
                               });
  MirrorResult m = measure_mirror(*fields, g, MirrorAxis::y, nullptr);
  m.scene_text = r.file.scene_text();
  return m;
}

// Mirror x → −x in a periodic box (node i ↔ N − 1 − i): u odd, v and ρ even.
// Taylor–Green-type field u = U sin kx cos ky, v = −U cos kx sin ky + ½U cos 2kx.
MirrorResult run_box_mirror(fluid::CollisionModel model, long steps, io::Series* trace) {
  const int N = 64;
  const Grid g{N, N};
  const vv::SceneFile& file = box_scene();
  std::vector<std::string> o = base(file, model, N, N, steps);
  o.push_back(vv::set("output.fields_interval_steps", 100L));
  const auto [r, fields] = run(file, o, std::string(fluid::to_string(model)) + "_box_mirror",
                               [&](sim::Simulation& simulation) {
                                 const double k = 2.0 * std::numbers::pi / N, U = 0.04;
                                 std::vector<double> rho(g.size()), ux(g.size()), uy(g.size());
                                 for (int j = 0; j < N; ++j) {
                                   for (int i = 0; i < N; ++i) {
                                     const double x = i + 0.5, y = j + 0.5;
                                     const auto n = g.index(i, j);
                                     ux[n] = U * std::sin(k * x) * std::cos(k * y);
                                     uy[n] = -U * std::cos(k * x) * std::sin(k * y) + 0.5 * U * std::cos(2 * k * x);
                                     rho[n] = 1.0 + 0.002 * std::cos(k * x) * std::sin(2 * k * y);
                                   }
                                 }
                                 simulation.fluid()->initialize(rho, ux, uy);
                               });
  MirrorResult m = measure_mirror(*fields, g, MirrorAxis::x, trace);
  m.scene_text = r.file.scene_text();
  return m;
}

// (c) Decay rate of the shear wave u_y = A sin(kx) on a uniform flow (ax, ay):
// Γ = ln(|û(t1)|/|û(t2)|)/(t2 − t1) from the k-th Fourier coefficient over x, which
// is insensitive to the translation of the wave by the advection.
struct DecayRate {
  double rate = 0, wall_time_s = 0;
  std::string scene_text;
};

DecayRate shear_wave_decay_rate(fluid::CollisionModel model, int N, double ax, double ay, double amplitude) {
  const Grid g{N, 4};
  const double k = 2.0 * std::numbers::pi / N;
  const long t_decay = std::lround(1.0 / (kNu * k * k));
  const long t1 = t_decay / 10, t2 = t_decay;
  const vv::SceneFile& file = box_scene();
  std::vector<std::string> o = base(file, model, g.nx, g.ny, t2);
  o.push_back(vv::set("output.fields_interval_steps", t1));
  o.push_back(vv::set("initial.type", "\"uniform\""));  // the carrier flow; the wave is added below
  o.push_back(vv::set("limits.max_mach", 0.3));
  o.push_back(vv::set_initial_velocity(file, o, {ax, ay}));
  char label[96];
  std::snprintf(label, sizeof label, "%s_shear_wave_N%d_a%.2f_%.2f", fluid::to_string(model).data(), N, ax, ay);
  const auto [r, fields] = run(file, o, label, [&](sim::Simulation& simulation) {
    fluid::FlowField start;
    start.resize(g.size(), true);
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < N; ++i) {
        const double x = i + 0.5;
        const auto n = g.index(i, j);
        start.ux[n] = ax;
        start.uy[n] = ay + amplitude * std::sin(k * x);
        start.duy_dx[n] = amplitude * k * std::cos(k * x);
      }
    }
    fluid::initialize_post_collision(*simulation.fluid(), start);
  });
  auto mode_amplitude = [&](long step) {
    const fluid::Moments& m = fields->at(step);
    std::complex<double> c = 0;
    for (int i = 0; i < N; ++i) c += m.uy[g.index(i, 0)] * std::exp(std::complex<double>(0, -k * (i + 0.5)));
    return std::abs(c);
  };
  return {std::log(mode_amplitude(t1) / mode_amplitude(t2)) / double(t2 - t1), r.summary.wall_time_s,
          r.file.scene_text()};
}
}  // namespace

TEST(GalileanSymmetry, UniformMirrorAndGalileanError) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.galilean_symmetry", "fluid");
  record.set_requirement(
      "(a) A uniform flow u0 = (0.1, 0.05) in a periodic box stays uniform (spread <= 1e-14 |u0|) and equal to u0 "
      "(<= 1e-13 relative) over 10^4 steps; (b) mirror-symmetric channel and periodic-box flows stay mirror-symmetric "
      "(velocity asymmetry <= 1e-13 of max|u|, density asymmetry <= 1e-14); (c) the decay rate of a shear wave "
      "advected along its wave vector at speed a changes by -3a^2 (relative, within 0.5% at N = 64), i.e. "
      "proportional to a^2, and not at all for advection along the wave's velocity; BGK and TRT.");
  record.set_reference(
      "(a), (b): symmetries of the D2Q9 scheme; (c): D2Q9 second-order equilibrium lacks rho u_a u_b u_c in its third "
      "moment, giving the stress error -(tau - 1/2) d_c(rho u_a u_b u_c) (Krueger et al. 2017, The Lattice Boltzmann "
      "Method, sec. 4.1; Dellar 2003, J Comput Phys 190:351), nu_eff = nu (1 - a^2/c_s^2) for u = (a, v(x)).");
  record.set_parameter("tau", kTau);
  record.set_parameter("trt_magic", 3.0 / 16.0);
  record.set_parameter("uniform_flow", std::string("u0 = (0.1, 0.05), 32 x 32 periodic, 10^4 steps"));
  record.set_parameter("channel_mirror",
                       std::string("32 x 32, walls at y = 0, 32, force 1e-5, start u = 0.02 (cos kx cos ky, "
                                   "sin kx sin ky), 3000 steps, mirror y -> 32 - y"));
  record.set_parameter("box_mirror", std::string("64 x 64 periodic, u = U sin kx cos ky, v = -U cos kx sin ky + "
                                                 "U/2 cos 2kx, U = 0.04, 2000 steps, mirror x -> -x"));
  record.set_parameter("shear_wave", std::string("u_y = 0.01 sin(kx) on (a_x, a_y), N x 4 periodic, decay rate "
                                                 "from t_d/10 to t_d = 1/(nu k^2)"));

  double worst_spread = 0, worst_deviation = 0, worst_velocity_asym = 0, worst_density_asym = 0;
  for (auto model : {fluid::CollisionModel::bgk, fluid::CollisionModel::trt}) {
    const std::string mname(fluid::to_string(model));
    const std::string label = model == fluid::CollisionModel::bgk ? "BGK" : "TRT";
    // (a)
    vv::Stopwatch clock;
    const UniformResult u1 = run_uniform(model, 0.1, 0.05, 1);
    const UniformResult u = run_uniform(model, 0.1, 0.05, 10000);
    record.add_run({{"part", std::string("a uniform")}, {"model", mname}, {"N", 32.0}, {"u0x", 0.1}, {"u0y", 0.05},
                    {"steps", 10000.0}, {"error", u.deviation}, {"spread", u.spread},
                    {"error_after_1_step", u1.deviation}, {"density_deviation", u.rho_deviation},
                    {"decay_rate_change", 0.0}, {"wall_time_s", clock.seconds()}},
                   u.scene_text);
    worst_spread = std::max(worst_spread, u.spread / std::hypot(0.1, 0.05));
    worst_deviation = std::max(worst_deviation, u.deviation);
    // (b)
    clock = vv::Stopwatch();
    const MirrorResult channel = run_channel_mirror(model, 3000);
    record.add_run({{"part", std::string("b channel mirror")}, {"model", mname}, {"N", 32.0}, {"u0x", 0.0},
                    {"u0y", 0.0}, {"steps", 3000.0}, {"error", channel.velocity_asymmetry}, {"spread", 0.0},
                    {"error_after_1_step", 0.0}, {"density_deviation", channel.density_asymmetry},
                    {"decay_rate_change", 0.0}, {"wall_time_s", clock.seconds()}},
                   channel.scene_text);
    clock = vv::Stopwatch();
    io::Series trace{"box_mirror_asymmetry_" + mname, label + ": x-mirror velocity asymmetry / max|u|, 64 x 64 box",
                     "step", "max |u + u_mirror| / max|u|", {}, {}, {}};
    const MirrorResult box = run_box_mirror(model, 2000, &trace);
    record.add_series(trace);
    record.add_run({{"part", std::string("b box mirror")}, {"model", mname}, {"N", 64.0}, {"u0x", 0.0},
                    {"u0y", 0.0}, {"steps", 2000.0}, {"error", box.velocity_asymmetry}, {"spread", 0.0},
                    {"error_after_1_step", 0.0}, {"density_deviation", box.density_asymmetry},
                    {"decay_rate_change", 0.0}, {"wall_time_s", clock.seconds()}},
                   box.scene_text);
    worst_velocity_asym = std::max({worst_velocity_asym, channel.velocity_asymmetry, box.velocity_asymmetry});
    worst_density_asym = std::max({worst_density_asym, channel.density_asymmetry, box.density_asymmetry});

    // (c) Galilean error of the decay rate, δ(a) = Γ(a)/Γ(0) − 1, predicted −3 a_x².
    io::SpeedErrorSeries speed{label, {}, {}, {}};
    io::Series coefficient{"galilean_coefficient_" + mname,
                           label + ": (Gamma(a)/Gamma(0) - 1) / (-3 a^2), a = 0.1 along k, against N", "N",
                           "measured / predicted", {}, {}, {}};
    for (int N : {32, 64, 128}) {
      const double k = 2.0 * std::numbers::pi / N;
      const DecayRate at_rest = shear_wave_decay_rate(model, N, 0.0, 0.0, 0.01);
      const double rest = at_rest.rate, rest_time = at_rest.wall_time_s;
      record.add_run({{"part", std::string("c shear wave")}, {"model", mname}, {"N", double(N)}, {"u0x", 0.0},
                      {"u0y", 0.0}, {"steps", std::round(1.0 / (kNu * k * k))},
                      {"error", std::abs(rest / (kNu * k * k) - 1.0)}, {"spread", 0.0},
                      {"error_after_1_step", 0.0}, {"density_deviation", 0.0}, {"decay_rate_change", 0.0},
                      {"wall_time_s", rest_time}},
                     at_rest.scene_text);
      speed.wall_time_s.push_back(rest_time);
      speed.error.push_back(std::abs(rest / (kNu * k * k) - 1.0));
      speed.label.push_back("shear wave at rest N=" + std::to_string(N));
      std::map<std::pair<double, double>, double> change;
      for (auto [ax, ay] : {std::pair{0.05, 0.0}, {0.1, 0.0}, {0.1, 0.05}, {0.0, 0.1}}) {
        const DecayRate advected = shear_wave_decay_rate(model, N, ax, ay, 0.01);
        change[{ax, ay}] = advected.rate / rest - 1.0;
        record.add_run({{"part", std::string("c shear wave")}, {"model", mname}, {"N", double(N)}, {"u0x", ax},
                        {"u0y", ay}, {"steps", std::round(1.0 / (kNu * k * k))},
                        {"error", std::abs(change[{ax, ay}] + 3.0 * ax * ax)}, {"spread", 0.0},
                        {"error_after_1_step", 0.0}, {"density_deviation", 0.0},
                        {"decay_rate_change", change[{ax, ay}]}, {"wall_time_s", advected.wall_time_s}},
                       advected.scene_text);
      }
      coefficient.x.push_back(N);
      coefficient.y.push_back(change[{0.1, 0.0}] / (-3.0 * 0.01));
      if (N != 64) continue;
      for (double a : {0.05, 0.1}) {
        const double c = change[{a, 0.0}] / (-3.0 * a * a);
        EXPECT_TRUE(record.add_metric(
            {"galilean coefficient " + label + " a=" + std::to_string(a).substr(0, 4),
             "(Gamma(a)/Gamma(0) - 1) / (-3 a^2), shear wave advected along k, N = 64", "", c, 1.0, 0.005,
             io::Comparison::absolute,
             "-3a^2 is the leading (Chapman-Enskog) term; the rest is an O(k^2) discretisation part, measured "
             "2e-3, 5e-4, 1.3e-4 at N = 32, 64, 128, and O(a^4) (ratio below)"}))
            << label << " a=" << a << " coefficient " << c;
      }
      const double ratio = change[{0.1, 0.0}] / change[{0.05, 0.0}];
      EXPECT_TRUE(record.add_metric({"galilean u0^2 scaling " + label,
                                     "delta(a = 0.1) / delta(a = 0.05), N = 64: 4 if delta is proportional to a^2",
                                     "", ratio, 4.0, 0.01, io::Comparison::absolute,
                                     "an a^4 term would shift the ratio by 4 x (0.1^2 - 0.05^2) x its relative size; "
                                     "0.01 (0.25%) allows it at 1/30 of the a^2 term"}))
          << label << " ratio " << ratio;
      EXPECT_TRUE(record.add_metric(
          {"no galilean error across " + label, "|Gamma(a)/Gamma(0) - 1| for advection (0, 0.1) along the wave's "
                                               "velocity, N = 64",
           "", std::abs(change[{0.0, 0.1}]), 1e-12, 0.0, io::Comparison::at_most,
           "for y-independent flow with u_x = 0 the y-momentum moments of f_eq are linear in u_y, so a uniform u_y "
           "superposes exactly: only round-off (measured <= 1e-13) remains"}))
          << label << " " << change[{0.0, 0.1}];
      EXPECT_TRUE(record.add_metric(
          {"galilean error diagonal " + label, "|delta(0.1, 0.05) - delta(0.1, 0)|, N = 64", "",
           std::abs(change[{0.1, 0.05}] - change[{0.1, 0.0}]), 1e-10, 0.0, io::Comparison::at_most,
           "the error term a_x^2 d_x v involves only the component along k; the cross terms u_x u_y u_y act in "
           "sigma_yy, which does not vary with y: only round-off of the decay-rate fit remains"}))
          << label;
    }
    record.add_series(coefficient);
    record.add_speed_error(speed);
  }
  EXPECT_TRUE(record.add_metric(
      {"uniform flow spread", "max over nodes and models of (max - min of u) / |u0| after 10^4 steps", "",
       worst_spread, 1e-14, 0.0, io::Comparison::at_most,
       "identical populations at every node: streaming is the identity and every node does the same floating-point "
       "operations, so the state is exactly uniform (measured 0); 1e-14 would still admit one-ulp differences "
       "between the vectorised interior and the scalar boundary code paths"}))
      << worst_spread;
  EXPECT_TRUE(record.add_metric(
      {"uniform flow value", "max over nodes and models of |u - u0| / |u0| after 10^4 steps", "", worst_deviation,
       1e-13, 0.0, io::Comparison::at_most,
       "the moments of f_eq(u0) reproduce u0 only to a few ulps (round-off of the equilibrium and of the sums); the "
       "state settles on a floating-point fixed point within 10 steps (identical at 10, 100, 1000, 10^4 steps), so "
       "nothing accumulates; 1e-13 is the issue's bound"}))
      << worst_deviation;
  EXPECT_TRUE(record.add_metric(
      {"mirror symmetry velocity", "max over runs of |u -+ u_mirror| / max|u| (channel, box; BGK, TRT)", "",
       worst_velocity_asym, 1e-13, 0.0, io::Comparison::at_most,
       "mirrored nodes hold permuted populations, and the kernel sums populations in a fixed index order, so the "
       "sums differ in the last bit; the flows are stable, so these ulp-level differences random-walk rather than "
       "grow (measured 1e-15 relative, rising only as the box flow decays under a fixed absolute round-off floor)"}))
      << worst_velocity_asym;
  EXPECT_TRUE(record.add_metric({"mirror symmetry density", "max over runs of |rho - rho_mirror|", "",
                                 worst_density_asym, 1e-14, 0.0, io::Comparison::at_most,
                                 "rho = 1 + sum of deviations: the mirrored sums differ by an ulp of 1 (2.2e-16); "
                                 "1e-14 allows a few tens of ulps"}))
      << worst_density_asym;
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
