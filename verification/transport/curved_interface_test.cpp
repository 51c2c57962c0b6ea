// Case verification.transport_curved_interface (issue 7 item 9;
// docs/transport.md §1 "Curved diffusivity jumps").
//
// Requirement: across a CURVED diffusivity jump cutting the lattice (a circular inclusion,
// D_in/D_out = 950/2800 as the RBC cytoplasm/plasma O2 pair), the face subpixel tensor (eqs
// T10–T11) converges at second order to the exact solution: least-squares order over
// n = 40, 56, 80, 112 nodes per side of 2 ± 0.25 for the far-field error (max over nodes
// farther than 0.1 from the membrane; the dipole problem, whose flux has a tangential part at
// the membrane, also in the L2 norm over all nodes); the former node series rule (T9) is first
// order in L2 for the dipole (order ≤ 1.5 asserted: the test discriminates) and ≥ 3× less
// accurate there at the finest level. For the deoxygenation cell's steady analogue (biconcave section,
// uniform source inside, held box) the heme-weighted mean changes by ≤ 0.02 % between h = 0.2
// and 0.15 µm with the face tensor (the case's 2 % requirement on M maps to ≈ 0.044 %, from
// Δln M ≈ −45 × relative change of this mean, measured with deoxy_probe). Mass balance closes
// to ≤ 1e−13 relative in every step.
// Reference: curved_interface.hpp — exact piecewise solutions (radial source: parabolic inside,
// logarithmic outside; dipole in a uniform gradient: B = (D_out − D_in)/(D_out + D_in)), C and
// D ∂C/∂r continuous at r = a (checked below), blended smoothly to the side values in a ring
// far from the membrane.
// Tolerances: 0.25 on the orders covers the scatter of a curved cut pattern over four levels
// (measured 1.99–2.05); the series bound 1.5 sits halfway between its measured 1.03 and 2.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/case_support.hpp"
#include "common/convergence.hpp"
#include "curved_interface.hpp"
#include "transport_run.hpp"

using namespace erythro;
using namespace erythro::vv;

namespace {

const std::vector<int> kLevels = {40, 56, 80, 112};
constexpr double kOrderTolerance = 0.25;
constexpr double kSeriesOrderBound = 1.5;
constexpr double kL2Advantage = 3.0;
constexpr double kCellMeanChange = 2e-4;

const char* name(InterfaceTreatment t) {
  return t == InterfaceTreatment::series ? "series" : t == InterfaceTreatment::node_tensor ? "node_tensor"
                                                                                           : "face_tensor";
}

struct Study {
  io::ConvergenceSeries far, l2;
  double finest_l2 = 0.0;
};

Study study(io::ResultRecord& rec, const Inclusion& p, InterfaceTreatment t, double& worst_balance) {
  const std::string label = std::string(p.problem == InclusionProblem::radial ? "radial " : "dipole ") + name(t);
  Study s{{label + " far field", "max |C - C_exact| / scale, |r - a| > 0.1", {}, {}, {}, 2.0, 0.0, kOrderTolerance,
           false, ""},
          {label + " L2", "RMS |C - C_exact| / scale, all nodes", {}, {}, {}, 2.0, 0.0, kOrderTolerance, false, ""}};
  for (int n : kLevels) {
    const InclusionRun r = run_inclusion(p, n, t);
    worst_balance = std::max(worst_balance, r.worst_mass_residual);
    rec.add_run({{"problem", std::string(p.problem == InclusionProblem::radial ? "radial" : "dipole")},
                 {"treatment", std::string(name(t))}, {"n", double(n)}, {"steps", double(r.steps)},
                 {"error_l2", r.error_l2}, {"error_max", r.error_max}, {"error_far", r.error_bulk},
                 {"error_cut_rms", r.error_cut}, {"error_inclusion_mean", r.error_mean},
                 {"mass_residual", r.worst_mass_residual}, {"wall_time_s", r.wall_s}},
                r.scene_text);
    s.far.h.push_back(2.0 / n);
    s.far.error.push_back(r.error_bulk);
    s.l2.h.push_back(2.0 / n);
    s.l2.error.push_back(r.error_l2);
    s.finest_l2 = r.error_l2;
  }
  fit_order(s.far);
  fit_order(s.l2);
  rec.add_convergence(s.far);
  rec.add_convergence(s.l2);
  return s;
}

io::Metric metric(const std::string& n, const std::string& d, double v, double e, io::Comparison c,
                  const std::string& why) {
  return {n, d, "", v, e, 0.0, c, why};
}

}  // namespace

TEST(TransportCurvedInterface, ExactSolutionsAreFluxContinuous) {
  for (auto problem : {InclusionProblem::radial, InclusionProblem::dipole}) {
    Inclusion p;
    p.problem = problem;
    for (double th : {0.0, 0.7, 2.0}) {
      const double eps = 1e-7, x = std::cos(th), y = std::sin(th);
      EXPECT_NEAR(p.concentration((p.a - eps) * x, (p.a - eps) * y), p.concentration((p.a + eps) * x, (p.a + eps) * y),
                  1e-6);
      EXPECT_NEAR(p.radial_flux(th, true), p.radial_flux(th, false), 1e-12);
      // D ∂C/∂r by differences on each side equals the stated flux
      const auto dr = [&](double r0, double D) {
        const double up = p.concentration((r0 + 1e-5) * x, (r0 + 1e-5) * y);
        const double down = p.concentration((r0 - 1e-5) * x, (r0 - 1e-5) * y);
        return D * (up - down) / 2e-5;
      };
      EXPECT_NEAR(dr(p.a - 1e-3, p.D_in), p.radial_flux(th, true), 2e-3);
      EXPECT_NEAR(dr(p.a + 1e-3, p.D_out), p.radial_flux(th, false), 2e-3);
    }
  }
}

TEST(TransportCurvedInterface, FaceTensorIsSecondOrder) {
  Stopwatch total;
  io::ResultRecord rec("verification.transport_curved_interface", "transport");
  rec.set_requirement(
      "Steady diffusion across a curved diffusivity jump (circular inclusion, D_in/D_out = 950/2800) on the D2Q5 "
      "TRT (Lambda = 1/4) lattice: the face subpixel tensor (transport eqs T10-T11) converges at order 2 +- 0.25 "
      "(least squares over n = 40, 56, 80, 112) in the far field (both problems) and in L2 (dipole); the node "
      "series rule (T9) is first order in L2 for the dipole (<= 1.5) and >= 3x less accurate there (finest level); "
      "steady biconcave cell: mean changes <= 0.02 % between h = 0.2 and 0.15 um with the face tensor; mass "
      "balance <= 1e-13 relative in every step.");
  rec.set_reference(
      "Exact piecewise solutions (curved_interface.hpp): radial source q0 inside (C_in parabolic, C_out "
      "logarithmic), dipole in a uniform gradient (B = (D_out - D_in)/(D_out + D_in)); C and D dC/dr continuous "
      "at r = a; smooth C4 blend to the side values in 0.7 < r < 0.95 with its manufactured source.");
  rec.set_parameter("levels", "n = 40, 56, 80, 112 nodes on [-1, 1]^2, inclusion radius a = 0.5 (20-56 nodes)");
  rec.set_parameter("lattice", "D2Q5, TRT Lambda = 1/4, D_out = 0.5 lattice units (steady TRT state depends on D "
                               "and Lambda only), readout C + q/(12 D) (eq T7)");
  rec.set_parameter("treatments", "series: node 1/D = phi/D_in + (1-phi)/D_out; node_tensor: eq T10 on each node's "
                                  "square (tensor lattice T8, recorded only); face_tensor: eq T10 on each face's dual "
                                  "cell through the face-flux correction T11");
  double worst = 0.0;
  for (auto problem : {InclusionProblem::dipole, InclusionProblem::radial}) {
    Inclusion p;
    p.problem = problem;
    const std::string tag = problem == InclusionProblem::radial ? "radial" : "dipole";
    const Study face = study(rec, p, InterfaceTreatment::face_tensor, worst);
    const Study series = study(rec, p, InterfaceTreatment::series, worst);
    const Study node = study(rec, p, InterfaceTreatment::node_tensor, worst);
    (void)node;
    EXPECT_TRUE(rec.add_metric(order_metric(face.far, "face subpixel tensor: second order expected (Kottke et al. "
                                                      "2008); 0.25 covers the scatter of the cut pattern")))
        << tag << " far " << face.far.observed_order;
    if (problem == InclusionProblem::dipole) {
      EXPECT_TRUE(rec.add_metric(order_metric(face.l2, "face subpixel tensor, all nodes (tangential flux at the "
                                                       "membrane)")))
          << face.l2.observed_order;
      EXPECT_TRUE(rec.add_metric(metric("order_series_dipole_l2", "least-squares L2 order of the node series rule "
                                        "(the former treatment)", series.l2.observed_order, kSeriesOrderBound,
                                        io::Comparison::at_most,
                                        "the series rule is first order with a tangential flux (measured 1.03): the "
                                        "case must tell the two apart")))
          << series.l2.observed_order;
      EXPECT_TRUE(rec.add_metric(metric("l2_ratio_series_over_face_dipole", "L2 error of the series rule / face "
                                        "tensor at n = 112", series.finest_l2 / face.finest_l2, kL2Advantage,
                                        io::Comparison::at_least, "measured 5.3; 3 leaves room for the cut pattern")))
          << series.finest_l2 / face.finest_l2;
    }
  }
  // The deoxygenation cell's steady analogue (h = 0.2 and 0.15 µm).
  for (auto t : {InterfaceTreatment::face_tensor, InterfaceTreatment::series}) {
    const double m20 = biconcave_steady_mean(0.2, t), m15 = biconcave_steady_mean(0.15, t);
    const double change = std::fabs(m15 - m20) / m15;
    rec.add_run({{"problem", std::string("biconcave")}, {"treatment", std::string(name(t))}, {"mean_h0.20", m20},
                 {"mean_h0.15", m15}, {"relative_change", change}});
    if (t == InterfaceTreatment::face_tensor) {
      EXPECT_TRUE(rec.add_metric(metric("biconcave_mean_change_face", "relative change of the steady heme-weighted "
                                        "mean between h = 0.2 and 0.15 um (face tensor)", change, kCellMeanChange,
                                        io::Comparison::at_most,
                                        "the case's 2 % on M is ~0.044 % of this mean; measured ~1e-6 (series: "
                                        "1.0e-3)")))
          << change;
    }
  }
  EXPECT_TRUE(rec.add_metric(mass_balance_metric(worst))) << worst;
  rec.set_wall_time(total.seconds());
  rec.write_to_results_dir();
  EXPECT_TRUE(rec.passed());
}
