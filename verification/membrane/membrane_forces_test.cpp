// Case verification.membrane_forces (issue 4 §5).
//
// Requirement: the discrete membrane forces (membrane/membrane_energy.hpp) are the
// exact negative gradient of the discrete energy, vanish at the rest shape, and have
// zero net force and torque for any deformation.
// Reference: E = Σ L_e W(λ_e) + ½E_B Σ(θ_i − θ0_i)²/D̄_i + ½k_A(A − A0)²/A0 (docs/model.md §3);
// F = −∂E/∂X checked by central differences; translation and rotation invariance of E.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "common/case_support.hpp"
#include "geometry/shapes.hpp"
#include "membrane/membrane_energy.hpp"

using namespace erythro;
using namespace erythro::membrane;
using namespace erythro::geometry;

namespace {

struct ShapeCase {
  const char* name;
  Polygon rest;  // origin-centred rest polygon
};

std::vector<ShapeCase> shapes() {
  return {{"circle", circle(48, 8.0)}, {"ellipse", ellipse(48, 10.0, 5.0)}, {"biconcave", biconcave(64, 10.0)}};
}

MembraneModel model_for(TensionLawType law) {
  // Moduli chosen so that the three energies are of similar size for the deformations used.
  return {{law, 0.02, 2.0}, 0.5, 0.01};
}

// Rigid placement plus a random perturbation of amplitude `noise` (lattice units).
Polygon deformed(const Polygon& rest, double stretch_x, double noise, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-noise, noise);
  Polygon p = rest;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.x[i] = p.x[i] * stretch_x + u(rng);
    p.y[i] = p.y[i] / std::sqrt(stretch_x) + u(rng);
  }
  return transformed(p, 1.0, 0.7, 103.3, 47.9);
}

double max_abs(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max({m, std::abs(a[i]), std::abs(b[i])});
  return m;
}

}  // namespace

TEST(MembraneForces, GradientRestAndInvariance) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.membrane_forces", "membrane");
  record.set_requirement(
      "Marker forces equal minus the central-difference gradient of the discrete energy (max relative error "
      "<= 1e-7), vanish at the rest shape (<= 1e-12 of the force scale) and have zero net force and torque "
      "(<= 1e-13 relative) for random deformations; three laws x three shapes, with bending and area terms.");
  record.set_reference(
      "Discrete energy of membrane/membrane_energy.hpp (docs/model.md sec. 3: tension law, bending m = E_B(kappa - "
      "kappa0), area penalty); forces as its exact gradient; invariance under rigid motions.");
  record.set_parameter("moduli", std::string("E_s = 0.02, Skalak C = 2, E_B = 0.5, k_A = 0.01 (lattice)"));
  record.set_parameter("fd_step", 1e-5);
  record.set_parameter("deformation", std::string("stretch 1.1 along x, area-preserving, plus uniform noise +-0.2"));

  std::mt19937_64 rng(42);
  const double eps = 1e-5;
  double worst_fd = 0.0, worst_rest = 0.0, worst_net = 0.0, worst_torque = 0.0, worst_forces_only = 0.0;
  for (TensionLawType law : {TensionLawType::neo_hookean, TensionLawType::skalak, TensionLawType::hookean}) {
    const MembraneModel model = model_for(law);
    for (const ShapeCase& sc : shapes()) {
      const vv::Stopwatch run_clock;
      const RestShape rest = RestShape::from_polygon(sc.rest);
      const std::size_t n = rest.size();
      // Rest shape, placed and rotated: zero force up to round-off.
      {
        const Polygon placed = transformed(sc.rest, 1.0, 0.7, 103.3, 47.9);
        std::vector<double> fx(n, 0.0), fy(n, 0.0);
        add_membrane_forces(model, rest, placed.x, placed.y, fx, fy);
        // Force scale of a unit deformation: E_s + E_B/Δs² + k_A·Δs·R ≈ O(1).
        worst_rest = std::max(worst_rest, max_abs(fx, fy));
      }
      const Polygon p = deformed(sc.rest, 1.1, 0.2, rng);
      std::vector<double> fx(n, 0.0), fy(n, 0.0);
      add_membrane_forces(model, rest, p.x, p.y, fx, fy);
      // The time step's path (no energy) must give the same forces, bit for bit.
      std::vector<double> gx(n, 0.0), gy(n, 0.0);
      add_membrane_forces_only(model, rest, p.x, p.y, gx, gy);
      for (std::size_t i = 0; i < n; ++i)
        worst_forces_only = std::max({worst_forces_only, std::abs(gx[i] - fx[i]), std::abs(gy[i] - fy[i])});
      const double fscale = max_abs(fx, fy);
      // Net force and torque (about the origin, far from the cell: the harder case).
      double Fx = 0, Fy = 0, M = 0, sum_abs = 0, torque_scale = 0;
      for (std::size_t i = 0; i < n; ++i) {
        Fx += fx[i];
        Fy += fy[i];
        M += p.x[i] * fy[i] - p.y[i] * fx[i];
        sum_abs += std::abs(fx[i]) + std::abs(fy[i]);
        torque_scale += std::hypot(p.x[i], p.y[i]) * std::hypot(fx[i], fy[i]);
      }
      const double net = std::hypot(Fx, Fy) / sum_abs, torque = std::abs(M) / torque_scale;
      worst_net = std::max(worst_net, net);
      worst_torque = std::max(worst_torque, torque);
      // Central differences of the total energy.
      double fd_err = 0.0;
      Polygon q = p;
      for (std::size_t i = 0; i < n; ++i) {
        for (int axis = 0; axis < 2; ++axis) {
          double& c = axis == 0 ? q.x[i] : q.y[i];
          const double c0 = c;
          c = c0 + eps;
          const double ep = membrane_energy(model, rest, q.x, q.y).total();
          c = c0 - eps;
          const double em = membrane_energy(model, rest, q.x, q.y).total();
          c = c0;
          const double f_fd = -(ep - em) / (2 * eps);
          fd_err = std::max(fd_err, std::abs(f_fd - (axis == 0 ? fx[i] : fy[i])) / fscale);
        }
      }
      worst_fd = std::max(worst_fd, fd_err);
      const Energy E = membrane_energy(model, rest, p.x, p.y);
      record.add_run({{"law", std::string(to_string(law))}, {"shape", std::string(sc.name)},
                      {"markers", double(n)}, {"energy_tension", E.tension}, {"energy_bending", E.bending},
                      {"energy_area", E.area}, {"max_force", fscale}, {"fd_rel_error", fd_err},
                      {"net_force_rel", net}, {"net_torque_rel", torque}, {"wall_time_s", run_clock.seconds()}});
    }
  }
  EXPECT_TRUE(record.add_metric({"fd_gradient_error", "max |F - F_fd| / max|F| over laws, shapes, markers", "",
                                 worst_fd, 1e-7, 0.0, io::Comparison::at_most,
                                 "central differences with step 1e-5 on O(1)-length edges: truncation "
                                 "O(eps^2 E'''/E') ~ 1e-10 plus round-off O(u E/(eps |F|)) ~ 1e-10; a wrong "
                                 "derivative term gives O(1) errors, so 1e-7 separates the two by 6 decades"}))
      << worst_fd;
  EXPECT_TRUE(record.add_metric({"forces_only_difference",
                                 "max |F(add_membrane_forces_only) - F(add_membrane_forces)|, the time step's path "
                                 "against the one that also returns the energy",
                                 "lattice force", worst_forces_only, 0.0, 0.0, io::Comparison::at_most,
                                 "the same operations for the forces, only the energy skipped: equal bit for bit"}))
      << worst_forces_only;
  EXPECT_TRUE(record.add_metric({"rest_force", "max |F| at the rest shape (placed at (103, 48), rotated)",
                                 "lattice force", worst_rest, 1e-12, 0.0, io::Comparison::at_most,
                                 "only the round-off of recomputing lengths, angles and area after a rigid "
                                 "motion remains: ~1e-14 relative on O(1) moduli"}))
      << worst_rest;
  EXPECT_TRUE(record.add_metric({"net_force", "|sum F| / sum |F| for random deformations", "", worst_net, 1e-13, 0.0,
                                 io::Comparison::at_most,
                                 "translation invariance makes the sum vanish identically; round-off of ~100 "
                                 "terms is ~1e-15"}))
      << worst_net;
  EXPECT_TRUE(record.add_metric({"net_torque", "|sum X x F| / sum |X||F| about the origin", "", worst_torque, 1e-13,
                                 0.0, io::Comparison::at_most,
                                 "rotation invariance makes the torque vanish identically; round-off ~1e-15"}))
      << worst_torque;
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
