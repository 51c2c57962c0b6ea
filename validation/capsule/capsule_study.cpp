#include "capsule_study.hpp"

#include <cmath>
#include <cstdio>

namespace erythro::vv::capsule {

bool same(double a, double b) { return std::abs(a - b) <= 1e-12 * std::abs(b); }

const std::vector<BimReference>& reference() {
  static const std::vector<BimReference> rows = read_bim_reference(ERYTHRO_CAPSULE_REFERENCE);
  return rows;
}

std::string case_tag(const BimReference& ref) { return ref.law + fmt("_G=%g", ref.G); }

CapsuleConfig config(const std::string& law, double G, double a, ib::KernelType kernel, double Re, double height,
                     double length) {
  CapsuleConfig c;
  c.law = law;
  c.kernel = kernel;
  c.capillary = G;
  c.radius = a;
  c.reynolds = Re;
  c.height = height;
  c.length = length;
  c.max_strain = kMaxStrain;
  c.area_projection = true;
  c.pictures = law == "neo_hookean" && kernel == ib::KernelType::cosine4 && same(G, 0.1) && a == 12 && Re == 0.1 &&
               height == 16;
  return c;
}

bool sharp(const BimReference& ref) {
  const double r = (1.0 + ref.D) / (1.0 - ref.D);
  return 5.0 * std::pow(r, 1.5) > 16.0;
}

double D_of(const CapsuleResult& r) { return r.D; }
double theta_of(const CapsuleResult& r) { return r.theta_deg; }
double period_of(const CapsuleResult& r) { return r.tt_period; }

Estimate estimate(const std::vector<double>& h, const std::vector<CapsuleResult>& levels, const Corrections& c,
                  Quantity q) {
  std::vector<double> v;
  for (const CapsuleResult& r : levels) v.push_back(q(r));
  Estimate e;
  e.rich = richardson(h, v, 1.0);
  const double q1 = q(c.re_0p1), q05 = q(c.re_0p05), q025 = q(c.re_0p025);
  e.d_re = 2.0 * q025 - q05 - q1;
  e.d_re_quad = (8.0 * q025 - 6.0 * q05 + q1) / 3.0 - q1;
  e.d_domain = q(c.wide) - q(c.narrow);
  e.value = e.rich.value + e.d_re + e.d_domain;
  return e;
}

std::string describe_estimate(const Estimate& e, const char* f) {
  return "Richardson " + fmt(f, e.rich.value) + " (order " + fmt("%.2f", e.rich.order) +
         (e.rich.observed ? " observed" : " assumed") + "), Re->0 " + fmt("%+.5f", e.d_re) + " (quadratic " +
         fmt("%+.5f", e.d_re_quad) + "), domain 16a->32a " + fmt("%+.5f", e.d_domain) + " -> " + fmt(f, e.value);
}

Estimates estimate_all(const std::vector<double>& h, const std::vector<CapsuleResult>& levels, const Corrections& c) {
  return {estimate(h, levels, c, D_of), estimate(h, levels, c, theta_of), estimate(h, levels, c, period_of)};
}

void record_estimates(io::ResultRecord& record, const BimReference& ref, const Estimates& e) {
  const std::string D = describe_estimate(e.D, "%.5f"), theta = describe_estimate(e.theta, "%.3f"),
                    T = describe_estimate(e.T, "%.4f");
  std::printf("%s: D %s ref %.5f | theta %s ref %.3f | T %s ref %.4f\n", case_tag(ref).c_str(), D.c_str(), ref.D,
              theta.c_str(), ref.theta_deg, T.c_str(), ref.T_gamma);
  record.set_parameter("extrapolation_" + case_tag(ref), "D: " + D + "; theta: " + theta + "; T gamma: " + T);
}

}  // namespace erythro::vv::capsule
