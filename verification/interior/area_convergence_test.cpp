// Case verification.interior_area_convergence (issue 5 item 5).
//
// Requirement: the cytoplasm volume the index field represents, Σ(1 − I) h², converges
// to the enclosed polygon area A at second order as the cell is resolved by more lattice
// spacings (circle, ellipse, biconcave), with the leading error the curvature term below.
//
// Derivation. For a closed curve whose offset curves at |s| < w are regular (curvature
// radius > w, no two parts of the membrane closer than 2w), the offset curve at signed
// distance s has length L(s) = P + s ∫κ dl = P + 2π s. The continuum integral of 1 − H(d)
// (eq 26, w = 2h) is then
//   ∫(1 − H) dA − A = ∫_{−w}^{w} g(s) (P + 2π s) ds,   g(s) = 1 − H(s) − [s < 0].
// H − ½ is odd, so g is odd: the P term vanishes (eq 26 has no zeroth-moment shift) and
//   E = 2π ∫ s g(s) ds = 4π ∫_0^w s (1 − H(s)) ds = (π/3 − 2/π) w² ≈ 0.4106 w² = 1.642 h²,
// a constant in lattice units, independent of the cell's size and shape. The relative error
// E/A ∝ (h/a)²: SECOND order. The lattice sum replacing the integral adds a quadrature
// error of a function that varies on the lattice scale; over a long curve its sign varies
// with the curve's position relative to the nodes and averages out (measured below as the
// residual after subtracting E). The biconcave dimple is 0.207a thick: below a ≈ 20h its
// two sides are closer than 2w, offset curves overlap and the derivation does not apply
// (that point is outside the asymptotic range; fitted from a = 24h up).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "common/case_support.hpp"
#include "common/convergence.hpp"
#include "geometry/shapes.hpp"
#include "interior/index_field.hpp"

using namespace erythro;
using namespace erythro::interior;
using namespace erythro::geometry;

namespace {
constexpr double kW = 2.0;
const double kCurvatureTerm = (std::numbers::pi / 3.0 - 2.0 / std::numbers::pi) * kW * kW;  // E, lattice units²
constexpr double kOrderTolerance = 0.1;

struct Shape {
  std::string name;
  std::vector<double> sizes;  // a in h
  geometry::Polygon (*make)(double a);
};

geometry::Polygon make_circle(double a) { return geometry::circle(std::max(100, int(std::ceil(4 * a))), a); }
geometry::Polygon make_ellipse(double a) { return geometry::ellipse(std::max(100, int(std::ceil(4 * a))), a, 0.55 * a); }
geometry::Polygon make_biconcave(double a) { return geometry::biconcave(std::max(100, int(std::ceil(4 * a))), a); }

struct AreaRun {
  double area, represented, error_rel, residual;
  long interior;
};

AreaRun measure(const geometry::Polygon& shape, double a) {
  const int n = static_cast<int>(std::ceil(2.6 * a)) + 12;
  const auto p = geometry::transformed(shape, 1.0, 0.37, 0.5 * n + 0.213, 0.5 * n + 0.071);
  IndexField f(geometry::Domain{Grid{n, n}, true, true}, {Method::flood_fill, kW});
  const FillReport& r = f.update(std::vector<geometry::Polygon>{p});
  double s = 0.0;
  for (double I : f.values()) s += 1.0 - I;
  const double A = geometry::signed_area(p);
  return {A, s, std::abs(s - A) / A, s - A - kCurvatureTerm, r.interior_nodes};
}
}  // namespace

TEST(InteriorAreaConvergence, SecondOrderWithCurvatureTerm) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.interior_area_convergence", "interior");
  record.set_requirement(
      "Sum(1 - I) h^2 of the flood-fill index field converges to the enclosed polygon area at second order in "
      "h/a (circle, ellipse 1:0.55, biconcave), the leading error being the curvature term (pi/3 - 2/pi) w^2 = "
      "1.642 h^2 derived from eq 26.");
  record.set_reference(
      "Offset-curve length L(s) = P + 2 pi s and the odd symmetry of H - 1/2 (eq 26, thesis section II.4) give "
      "Sum(1 - I) - A -> 4 pi int_0^w s (1 - H) ds = (pi/3 - 2/pi) w^2 (derivation in area_convergence_test.cpp).");
  record.set_parameter("band_half_width_h", kW);
  record.set_parameter("curvature_term_h2", kCurvatureTerm);
  record.set_parameter("placement", std::string("rotated 0.37 rad, centre offset (0.213, 0.071) h from a node corner"));
  record.set_parameter("markers", std::string("max(100, 4a/h)"));
  const std::vector<Shape> shapes{{"circle", {6, 12, 24, 48, 96}, make_circle},
                                  {"ellipse", {6, 12, 24, 48, 96}, make_ellipse},
                                  {"biconcave", {24, 48, 96, 192}, make_biconcave}};
  for (const Shape& sh : shapes) {
    io::ConvergenceSeries s;
    s.name = sh.name;
    s.norm = "|Sum(1 - I) - A| / A";
    s.formal_order = 2.0;
    s.order_tolerance = kOrderTolerance;
    double worst_residual = 0.0;
    for (double a : sh.sizes) {
      vv::Stopwatch clock;
      const AreaRun r = measure(sh.make(a), a);
      std::cout << sh.name << " a=" << a << " A=" << r.area << " sum=" << r.represented << " rel=" << r.error_rel
                << " sum-A=" << r.represented - r.area << " residual=" << r.residual << "\n";
      record.add_run({{"shape", sh.name}, {"a_h", a}, {"area_h2", r.area}, {"sum_1_minus_I_h2", r.represented},
                      {"interior_nodes", double(r.interior)}, {"error_rel", r.error_rel},
                      {"difference_h2", r.represented - r.area}, {"residual_after_curvature_term_h2", r.residual},
                      {"wall_time_s", clock.seconds()}});
      s.h.push_back(1.0 / a);
      s.error.push_back(r.error_rel);
      worst_residual = std::max(worst_residual, std::abs(r.residual));
    }
    vv::fit_order(s);
    record.add_convergence(s);
    EXPECT_TRUE(record.add_metric(vv::order_metric(
        s, "formal order 2: the error is the constant curvature term (pi/3 - 2/pi) w^2 over A ~ a^2 plus a smaller "
           "lattice quadrature residual; 0.1 allows that residual")))
        << s.name << " " << s.observed_order;
    EXPECT_TRUE(record.add_metric(vv::asymptotic_metric(s))) << s.name;
    EXPECT_TRUE(record.add_metric({"curvature term residual " + sh.name,
                                   "max |Sum(1 - I) - A - (pi/3 - 2/pi) w^2| over the sizes", "h^2", worst_residual,
                                   0.05, 0.0, io::Comparison::at_most,
                                   "the derived constant explains the error; the remaining lattice-quadrature part "
                                   "(measured <= 0.007 h^2 from a = 6 h up) stays 30x below the 1.64 h^2 term; 0.05 "
                                   "leaves a 7x margin for other placements"}))
        << sh.name << " residual " << worst_residual;
  }
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
