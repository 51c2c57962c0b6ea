// Case verification.interior_layered_flow (issue 5 item 6).
//
// Requirement: a flat "membrane" (the lower edge of a slab polygon, the cytoplasm above
// it) sets the viscosity of a channel flow through the index field (flood fill, eq 26
// band, eq 27 via IndexField::write_relaxation_times on FluidLattice::enable_tau_field);
// viscosity ratio 5 (6.0 / 1.2 cP). The velocity must equal the discrete prediction of
// the smeared profile to round-off and converge to the exact sharp two-layer solution at
// the order the band allows, derived here.
//
// Set-up: walls at y = 0 (rest) and y = N (Couette: speed U; Poiseuille: body force F),
// interface y = N/2 midway between node rows, plasma below (ν_ex, τ = 0.7), cytoplasm
// above (ν_in = 5 ν_ex, τ = 1.5). Slab polygon x ∈ [−8, 9], y ∈ [N/2, N + 8] on an
// index-field domain with walls on every side (its other edges lie beyond the walls and
// drop out), one periodic fluid column (x-invariant flow). Diffusive scaling, max u =
// 0.32/N. Exact solution: verification/fluid/vv4_layers.cpp (two_layer_exact).
// Runs: verification/fluid/channel.toml (nx = 1, plasma τ = 0.7, a moving top wall or a
// [body_force]); the slab is a fixed shape, so its index field is computed once and its τ
// written into the fluid's τ field before the run (CaseRunOptions::configure).
//
// Derivation (steady unidirectional flow; layered_viscosity_test.cpp, relation (ii)): a
// link between rows j, j+1 sees the harmonic mean of the node viscosities, so for Couette
// (σ constant) u_j = σ_d (Σ_{k<j} 1/ν_k + ½/ν_j), σ_d = U / Σ_k 1/ν_k, for ANY node
// viscosities, and away from the band u is the sharp solution with σ replaced by σ_d.
// The flow's resistance error is the band's δR = Σ_band [1/ν_j − 1/ν_sharp(y_j)] (h = 1):
//  • eq 27 blends μ (hence ν) linearly in I: 1/ν is convex in I, so for each pair of band
//    nodes at ±d, 1/ν(H) + 1/ν(1 − H) ≤ 1/ν_in + 1/ν_ex (Jensen): δR < 0, the smeared
//    band is less resistive, as if the sharp interface were moved by s = −δR/(1/ν_ex −
//    1/ν_in) into the plasma (measured s = 0.63 h for ratio 5, w = 2h). δR is independent of
//    N (the band has the same 4 nodes at every N): relative error |δR|/R_d ∝ 1/N — FIRST
//    order in h, i.e. proportional to the band width w/H. Continuum form: δR = ∫_{−w}^{w}
//    [1/ν(H(s)) − 1/ν_sharp(s)] ds = w·c(ν_in/ν_ex): first order in the band width, not
//    O(w²). The global error is |δR|/(R + δR) + band-node terms, c/(N + c'): its local
//    order approaches 1 from below (0.74, 0.89, 0.95 over N = 8…64).
//  • a harmonic blend (1/ν linear in I) has δR = (1/ν_ex − 1/ν_in) Σ_band [H(d_j) − χ(d_j)]
//    = 0 by the odd symmetry of H − ½ when nodes sit symmetrically about the interface
//    (midway placement): the outer flow is exact, only the 4 band nodes keep an O(h)
//    error (global relative L2 ~ h^1.5). Reported for comparison (not the thesis's rule).
//  Poiseuille adds O(F) interface and wall terms (O(h²)); the O(h) band term dominates.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <map>

#include "channel_flows.hpp"
#include "common/case_support.hpp"
#include "common/convergence.hpp"
#include "fluid_scenes.hpp"
#include "interior/index_field.hpp"
#include "simulation/simulation.hpp"
#include "vv4_layers.hpp"

using namespace erythro;
using namespace erythro::interior;
using namespace erythro::geometry;

namespace {
constexpr double kNuEx = 0.2 / 3.0;        // plasma, τ = 0.7
constexpr double kNuIn = 5.0 * kNuEx;      // cytoplasm, ratio 6.0/1.2 (docs/model.md §5), τ = 1.5
constexpr double kResidual = 1e-12;
constexpr int kResolutions[] = {8, 16, 32, 64};

enum class Blend { arithmetic, harmonic };  // eq 27 (ν linear in I) | 1/ν linear in I

struct LayerRun {
  double error_l2 = 0, error_far = 0, discrete_dev = 0, predicted_far = 0, wall_time_s = 0;
  double lower_dev = 0;       // max over lower outer rows of |(u − u_ex)/u_ex − (R/R_d − 1)|
  double interface_shift = 0; // δR / (1/ν_ex − 1/ν_in): the sharp interface's equivalent shift (h)
  long steps = 0, band_nodes = 0;
  std::vector<double> ux, exact;
  std::string scene_text;
};

std::string label(vv::LayerFlow f, fluid::CollisionModel m, Blend b);

LayerRun run(vv::LayerFlow flow, fluid::CollisionModel model, Blend blend, int N) {
  vv::TwoLayerProblem p{flow, vv::InterfacePlacement::midpoint, N, kNuEx, kNuIn, 1.0};
  double umax = 0.0;
  for (int j = 0; j < N; ++j) umax = std::max(umax, std::abs(vv::two_layer_exact(p, j + 0.5)));
  p.drive = 0.32 / N / umax;

  // The membrane: slab y ∈ [N/2, N + 8], markers every 0.5 h along its edges.
  geometry::Polygon slab;
  const double a = 0.5 * N, top = N + 8.0;
  for (double x = -8.0; x < 9.0; x += 0.5) { slab.x.push_back(x); slab.y.push_back(a); }
  for (double y = a; y < top; y += 0.5) { slab.x.push_back(9.0); slab.y.push_back(y); }
  for (double x = 9.0; x > -8.0; x -= 0.5) { slab.x.push_back(x); slab.y.push_back(top); }
  for (double y = top; y > a; y -= 0.5) { slab.x.push_back(-8.0); slab.y.push_back(y); }
  // A static shape: its index field (eq 26) is computed once, here.
  IndexField field(geometry::Domain{Grid{1, N}, false, false}, {Method::flood_fill, 2.0});
  const FillReport& rep = field.update(std::vector<geometry::Polygon>{slab});
  std::vector<double> tau(static_cast<std::size_t>(N));
  if (blend == Blend::arithmetic) {
    field.write_relaxation_times(tau, kNuIn, kNuEx);  // eq 27
  } else {
    for (int j = 0; j < N; ++j) {
      const double I = field.values()[static_cast<std::size_t>(j)];
      tau[static_cast<std::size_t>(j)] = 0.5 + 3.0 / (1.0 / kNuIn + (1.0 / kNuEx - 1.0 / kNuIn) * I);
    }
  }

  // The channel scene (the plasma is the fluid), its τ field written before the run.
  static const vv::SceneFile channel("verification/fluid/channel.toml");
  std::vector<std::string> o = {vv::set_grid(1, N), vv::set_collision(model),
                                vv::set("run.steps", vv::steps_to_steady_state(N, kNuEx, kResidual)),
                                vv::set("limits.max_mach", 0.5)};  // the speed estimate assumes plasma everywhere
  o.push_back(vv::set_tau(channel, o, 0.5 + 3.0 * kNuEx));
  if (flow == vv::LayerFlow::couette) {
    o.push_back(vv::set("boundaries.top.type", "\"moving_wall\""));
    o.push_back(vv::set_top_wall_velocity(channel, o, p.drive));
  } else {
    o.push_back(vv::set_body_force(channel, o, {p.drive, 0.0}));
  }
  vv::CaseRunOptions options;
  options.configure = [&](sim::Simulation& simulation) {
    fluid::FluidLattice& lattice = *simulation.fluid();
    lattice.enable_tau_field();
    std::copy(tau.begin(), tau.end(), lattice.tau_field().begin());
  };
  const std::string tag = label(flow, model, blend) + " N=" + std::to_string(N);
  const vv::ChannelResult ch = vv::run_channel(channel, o, "verification.interior_layered_flow", tag, options);

  LayerRun r;
  r.steps = ch.steps;
  r.wall_time_s = ch.wall_time_s;
  r.ux = ch.ux;
  r.scene_text = ch.scene_text;
  r.band_nodes = rep.band_nodes;
  // Discrete Couette prediction from the node viscosities actually set.
  std::vector<double> nu(static_cast<std::size_t>(N));
  double R_d = 0.0, R = a / kNuEx + (N - a) / kNuIn;
  for (int j = 0; j < N; ++j) {
    nu[static_cast<std::size_t>(j)] = (tau[static_cast<std::size_t>(j)] - 0.5) / 3.0;
    R_d += 1.0 / nu[static_cast<std::size_t>(j)];
  }
  double far_e2 = 0, far_u2 = 0, acc = 0, dev = 0, u_max = 0;
  for (int j = 0; j < N; ++j) {
    const double ex = vv::two_layer_exact(p, j + 0.5), u = r.ux[static_cast<std::size_t>(j)];
    r.exact.push_back(ex);
    u_max = std::max(u_max, std::abs(ex));
    if (p.far_from_interface(j)) {
      far_e2 += (u - ex) * (u - ex);
      far_u2 += ex * ex;
      if (j + 0.5 < a) r.lower_dev = std::max(r.lower_dev, std::abs((u - ex) / ex - (R / R_d - 1.0)));
    }
    const double ud = p.drive / R_d * (acc + 0.5 / nu[static_cast<std::size_t>(j)]);
    acc += 1.0 / nu[static_cast<std::size_t>(j)];
    dev = std::max(dev, std::abs(u - ud));
  }
  r.error_l2 = vv::relative_l2(r.ux, r.exact);
  r.error_far = std::sqrt(far_e2 / far_u2);
  r.discrete_dev = flow == vv::LayerFlow::couette ? dev / u_max : std::numeric_limits<double>::quiet_NaN();
  r.predicted_far = std::abs(R / R_d - 1.0);  // lower layer: u = σ_d y/ν_ex vs σ y/ν_ex
  r.interface_shift = (R - R_d) / (1.0 / kNuEx - 1.0 / kNuIn);  // > 0: cytoplasm appears thicker
  if (flow != vv::LayerFlow::couette) r.lower_dev = std::numeric_limits<double>::quiet_NaN();
  return r;
}

std::string label(vv::LayerFlow f, fluid::CollisionModel m, Blend b) {
  return vv::to_string(f) + " " + (m == fluid::CollisionModel::bgk ? "BGK" : "TRT(3/16)") + " " +
         (b == Blend::arithmetic ? "eq27-arithmetic" : "harmonic");
}
}  // namespace

TEST(InteriorLayeredFlow, IndexFieldViscosityMatchesDerivedAccuracy) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.interior_layered_flow", "interior");
  record.set_requirement(
      "Two-layer Couette and Poiseuille flow (viscosity ratio 5) with the viscosity set by the flood-fill index "
      "field of a flat membrane (eq 26 band of width 4h, eq 27 tau via write_relaxation_times) equals the discrete "
      "prediction of the smeared profile to round-off (Couette) and converges to the exact sharp-interface solution "
      "at first order in h (error proportional to the band width, eq 27's arithmetic blend); a harmonic blend makes "
      "the outer Couette flow exact.");
  record.set_reference(
      "Exact: sigma = mu du/dy continuous, piecewise linear/parabolic u (vv4_layers.cpp, two_layer_exact). Scheme: "
      "each link sees the harmonic mean of its nodes' viscosities (layered_viscosity_test.cpp relation (ii)), so "
      "the resistance error is dR = sum_band (1/nu_j - 1/nu_sharp) = const: relative error dR/R ~ w/H "
      "(derivation in layered_flow_test.cpp).");
  record.set_parameter("viscosity_ratio", 5.0);
  record.set_parameter("tau_plasma", 0.5 + 3 * kNuEx);
  record.set_parameter("tau_cytoplasm", 0.5 + 3 * kNuIn);
  record.set_parameter("band_half_width_h", 2.0);
  record.set_parameter("resolutions", std::string("N = 8, 16, 32, 64; interface y = N/2 (midway between rows)"));
  record.set_parameter("steady_state_residual", kResidual);

  struct Config {
    vv::LayerFlow flow;
    fluid::CollisionModel model;
    Blend blend;
  };
  const std::vector<Config> configs{
      {vv::LayerFlow::couette, fluid::CollisionModel::bgk, Blend::arithmetic},
      {vv::LayerFlow::couette, fluid::CollisionModel::trt, Blend::arithmetic},
      {vv::LayerFlow::couette, fluid::CollisionModel::bgk, Blend::harmonic},
      {vv::LayerFlow::poiseuille, fluid::CollisionModel::bgk, Blend::arithmetic},
      {vv::LayerFlow::poiseuille, fluid::CollisionModel::trt, Blend::arithmetic}};
  double worst_dev = 0.0, worst_pred = 0.0, shift_min = 1e300, shift_max = -1e300;
  std::map<std::string, io::SpeedErrorSeries> speed;
  for (const Config& c : configs) {
    const std::string tag = label(c.flow, c.model, c.blend);
    io::ConvergenceSeries s;
    s.name = tag + " global L2";
    s.norm = "relative L2 velocity error vs the sharp two-layer solution";
    double worst_far = 0.0;
    for (int N : kResolutions) {
      const LayerRun r = run(c.flow, c.model, c.blend, N);
      std::cout << tag << " N=" << N << " l2=" << r.error_l2 << " far=" << r.error_far << " pred_lower="
                << r.predicted_far << " lower_dev=" << r.lower_dev << " shift=" << r.interface_shift << " discrete_dev=" << r.discrete_dev << " steps=" << r.steps
                << " t=" << r.wall_time_s << "\n";
      record.add_run({{"flow", vv::to_string(c.flow)}, {"model", std::string(fluid::to_string(c.model))},
                      {"blend", c.blend == Blend::arithmetic ? std::string("eq27_arithmetic") : std::string("harmonic")},
                      {"N", double(N)}, {"band_nodes", double(r.band_nodes)}, {"steps", double(r.steps)},
                      {"error_l2", r.error_l2}, {"error_far_l2", r.error_far},
                      {"predicted_lower_layer_error", r.predicted_far}, {"lower_layer_deviation", r.lower_dev},
                      {"interface_shift_h", r.interface_shift}, {"discrete_prediction_dev", r.discrete_dev},
                      {"wall_time_s", r.wall_time_s}},
                     r.scene_text);
      s.h.push_back(1.0 / N);
      s.error.push_back(r.error_l2);
      worst_far = std::max(worst_far, r.error_far);
      if (c.flow == vv::LayerFlow::couette) {
        worst_dev = std::max(worst_dev, r.discrete_dev);
        if (c.blend == Blend::arithmetic) {  // lower-layer relative error is exactly R/R_d − 1
          worst_pred = std::max(worst_pred, r.lower_dev);
          shift_min = std::min(shift_min, r.interface_shift);
          shift_max = std::max(shift_max, r.interface_shift);
        }
      }
      if (c.flow == vv::LayerFlow::poiseuille && c.blend == Blend::arithmetic) {
        auto& se = speed[tag];
        se.name = tag;
        se.wall_time_s.push_back(r.wall_time_s);
        se.error.push_back(r.error_l2);
        se.label.push_back("N=" + std::to_string(N));
      }
      if (N == 32 && c.model == fluid::CollisionModel::bgk) {
        io::Series prof{"profile " + tag + " N=32", tag + ", N = 32, interface y/H = 0.5", "y/H", "u / max u_exact",
                        {}, {}, {}};
        for (int j = 0; j < N; ++j) {
          prof.x.push_back((j + 0.5) / N);
          prof.y.push_back(r.ux[static_cast<std::size_t>(j)] * N / 0.32);
          prof.y_reference.push_back(r.exact[static_cast<std::size_t>(j)] * N / 0.32);
        }
        record.add_series(prof);
      }
    }
    const bool harmonic = c.blend == Blend::harmonic, couette = c.flow == vv::LayerFlow::couette;
    s.formal_order = harmonic ? 1.5 : 1.0;
    s.order_tolerance = couette ? 0.1 : 0.2;
    vv::fit_order(s);
    record.add_convergence(s);
    if (harmonic) {
      EXPECT_TRUE(record.add_metric(vv::order_metric(
          s, "formal 1.5: outer flow exact, the 4 band nodes keep an O(h) error (relative L2 ~ h^1.5), a single "
             "error term: 0.1 allows round-off")))
          << s.name << " " << s.observed_order;
      EXPECT_TRUE(record.add_metric(vv::asymptotic_metric(s))) << s.name;
    } else if (couette) {
      // c/(N + c'): judged on the finest local order (the least-squares slope over N = 8…64 is 0.87).
      bool falls = true;
      for (double q : s.local_orders) falls = falls && q > 0.0;
      const double finest = falls ? s.local_orders.back() : std::numeric_limits<double>::quiet_NaN();
      EXPECT_TRUE(record.add_metric({"finest local order " + s.name, "local order between N = 32 and 64, " + s.norm,
                                     "", finest, 1.0, 0.1, io::Comparison::absolute,
                                     "formal 1: the constant band resistance error dR against R ~ N (proportional to "
                                     "the band width w/H), error |dR|/(R + dR) ~ c/(N + c'): local order 0.95 at "
                                     "N = 32-64 (exactly predicted, see the lower-layer metric); 0.1 separates 1 from "
                                     "1.5 and 2"}))
          << s.name << " finest " << finest;
    } else {
      // Two terms: the O(h) band term and the O(F) = O(h^2) interface/wall terms of opposite
      // sign, which bias the least-squares slope at N <= 64: judged on the finest local order.
      bool falls = true;
      for (double q : s.local_orders) falls = falls && q > 0.0;
      const double finest = falls ? s.local_orders.back() : std::numeric_limits<double>::quiet_NaN();
      EXPECT_TRUE(record.add_metric({"finest local order " + s.name, "local order between N = 32 and 64, " + s.norm,
                                     "", finest, 1.0, 0.2, io::Comparison::absolute,
                                     "formal 1 (band resistance) plus an O(h^2) term (O(F) interface and wall terms) "
                                     "whose bias is still 0.1-0.15 at N = 64 (measured 0.92 BGK, 0.85 TRT; 0.96 "
                                     "between 64 and 128); 0.2 separates orders 1 and 2"}))
          << s.name << " finest " << finest;
    }
    if (harmonic && c.flow == vv::LayerFlow::couette) {
      EXPECT_TRUE(record.add_metric({"outer-flow error " + tag, "max relative L2 error over |y - H/2| > H/4", "",
                                     worst_far, 1e-9, 0.0, io::Comparison::at_most,
                                     "dR = 0 by the odd symmetry of eq 26 (nodes symmetric about the interface): "
                                     "exact up to round-off and the 1e-12 steady-state residual"}))
          << worst_far;
    }
  }
  EXPECT_TRUE(record.add_metric({"discrete Couette prediction", "max |u - u_discrete| / max u over the Couette runs, "
                                 "u_discrete from the node viscosities the index field set", "", worst_dev, 1e-9, 0.0,
                                 io::Comparison::at_most,
                                 "exact identity of the steady scheme (harmonic link rule); round-off and the 1e-12 "
                                 "steady-state residual remain"}))
      << worst_dev;
  EXPECT_TRUE(record.add_metric({"lower-layer error equals R/R_d - 1", "max over lower outer rows and N of "
                                 "|(u - u_exact)/u_exact - (R/R_d - 1)|, Couette, eq 27 blend", "", worst_pred, 1e-9,
                                 0.0, io::Comparison::at_most,
                                 "below the band u = sigma_d y / nu_ex exactly: the relative error is the resistance "
                                 "ratio; round-off and the 1e-12 residual remain"}))
      << worst_pred;
  // The band's resistance error as an equivalent shift of a sharp interface (constant in N).
  EXPECT_TRUE(record.add_metric({"interface shift spread", "max - min over N of dR/(1/nu_ex - 1/nu_in) (h)", "h",
                                 shift_max - shift_min, 1e-9, 0.0, io::Comparison::at_most,
                                 "the band has the same 4 nodes at the same offsets at every N: dR is constant, "
                                 "hence the first-order error"}))
      << shift_min << " " << shift_max;
  EXPECT_TRUE(record.add_metric({"interface shift", "equivalent shift of a sharp interface into the plasma, "
                                 "-dR/(1/nu_ex - 1/nu_in), eq 27 blend, ratio 5", "h", shift_max, 0.0, 0.0,
                                 io::Comparison::at_least,
                                 "Jensen: 1/nu is convex in I under eq 27, so the smeared band is less resistive "
                                 "(shift > 0); measured value reported (0.63 h)"}))
      << shift_max;
  record.set_parameter("interface_shift_h", shift_max);
  for (auto& [k, se] : speed) record.add_speed_error(se);
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
