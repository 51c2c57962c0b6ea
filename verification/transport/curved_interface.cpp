#include "curved_interface.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/case_support.hpp"
#include "simulation/simulation.hpp"
#include "transport/subpixel_diffusivity.hpp"
#include "transport_run.hpp"

namespace erythro::vv {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string fmt_h(double h) {
  char b[32];
  std::snprintf(b, sizeof b, "h%.3f", h);
  return b;
}

// C⁴ smoothstep S(t) = t⁵(126 − 420 t + 540 t² − 315 t³ + 70 t⁴) on [0, 1] and its derivatives.
double step(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * t * t * t * (126.0 + t * (-420.0 + t * (540.0 + t * (-315.0 + 70.0 * t))));
}
double step_d1(double t) {
  if (t <= 0.0 || t >= 1.0) return 0.0;
  const double u = t * (1.0 - t);
  return 630.0 * u * u * u * u;
}
double step_d2(double t) {
  if (t <= 0.0 || t >= 1.0) return 0.0;
  const double u = t * (1.0 - t);
  return 2520.0 * u * u * u * (1.0 - 2.0 * t);
}

struct Blend {
  double R1, R2;
  double chi(double r) const { return 1.0 - step((r - R1) / (R2 - R1)); }
  double chi_d1(double r) const { return -step_d1((r - R1) / (R2 - R1)) / (R2 - R1); }
  double chi_d2(double r) const { return -step_d2((r - R1) / (R2 - R1)) / ((R2 - R1) * (R2 - R1)); }
  // ∫_r^{R2} χ(s)/s ds for R1 ≤ r ≤ R2: 20-point Gauss–Legendre on 4 panels (smooth integrand)
  double integral_chi_over_s(double r) const {
    static const double xg[5] = {0.0765265211334973, 0.2277858511416451, 0.3737060887154195, 0.5108670019508271,
                                 0.6360536807265150};
    static const double xg2[5] = {0.7463319064601508, 0.8391169718222188, 0.9122344282513259, 0.9639719272779138,
                                  0.9931285991850949};
    static const double wg[5] = {0.1527533871307258, 0.1491729864726037, 0.1420961093183820, 0.1316886384491766,
                                 0.1181945319615184};
    static const double wg2[5] = {0.1019301198172404, 0.0832767415767048, 0.0626720483341091, 0.0406014298003869,
                                  0.0176140071391521};
    double s = 0.0;
    const int panels = 4;
    const double width = (R2 - r) / panels;
    for (int p = 0; p < panels; ++p) {
      const double mid = r + (p + 0.5) * width, half = 0.5 * width;
      for (int k = 0; k < 5; ++k) {
        for (double sign : {-1.0, 1.0}) {
          const double x1 = mid + sign * half * xg[k], x2 = mid + sign * half * xg2[k];
          s += half * (wg[k] * chi(x1) / x1 + wg2[k] * chi(x2) / x2);
        }
      }
    }
    return s;
  }
};

}  // namespace

double Inclusion::concentration(double x, double y) const {
  const double r = std::hypot(x, y);
  const Blend b{R1, R2};
  if (problem == InclusionProblem::radial) {
    const double A = q0 * a * a / (2.0 * D_out);
    auto outer = [&](double rr) {
      if (rr >= R2) return C_b;
      if (rr <= R1) return C_b + A * (std::log(R1 / rr) + b.integral_chi_over_s(R1));
      return C_b + A * b.integral_chi_over_s(rr);
    };
    if (r >= a) return outer(r);
    return outer(a) + q0 * (a * a - r * r) / (4.0 * D_in);
  }
  const double B = (D_out - D_in) / (D_out + D_in);
  if (r < a) return G * (1.0 + B) * x;
  return G * x * (1.0 + B * a * a * b.chi(r) / (r * r));
}

double Inclusion::source(double x, double y) const {
  const double r = std::hypot(x, y);
  const Blend b{R1, R2};
  if (problem == InclusionProblem::radial) {
    if (r < a) return q0;
    return r > R1 && r < R2 ? 0.5 * q0 * a * a * b.chi_d1(r) / r : 0.0;
  }
  if (r <= R1 || r >= R2) return 0.0;
  const double B = (D_out - D_in) / (D_out + D_in);
  return -D_out * G * B * a * a * (b.chi_d2(r) - b.chi_d1(r) / r) * x / (r * r);
}

double Inclusion::scale() const {
  return problem == InclusionProblem::radial ? concentration(0.0, 0.0) - C_b : G;
}

double Inclusion::radial_flux(double theta, bool inside) const {
  if (problem == InclusionProblem::radial) return -0.5 * q0 * a;  // both sides: −q0 a/2
  const double B = (D_out - D_in) / (D_out + D_in);
  // C_in = G(1+B) r cosθ, C_out = G (r + B a²/r) cosθ (χ = 1 near r = a)
  return inside ? D_in * G * (1.0 + B) * std::cos(theta) : D_out * G * (1.0 - B) * std::cos(theta);
}

namespace {

const char* interface_name(InterfaceTreatment t) {
  return t == InterfaceTreatment::series ? "\"series\"" : t == InterfaceTreatment::node_tensor ? "\"node_tensor\""
                                                                                            : "\"face_tensor\"";
}

// All four sides held at `value` (the dipole's scene holds left and right only).
void hold_all_sides(std::vector<std::string>& set_up, double value) {
  for (const char* side : {"bottom", "top"}) set_up.push_back(set(std::string("species[0].") + side, std::string("\"fixed_concentration\"")));
  for (const char* side : {"left", "right", "bottom", "top"}) set_up.push_back(set(std::string("species[0].") + side + "_value", value));
}

// The overrides of curved_interface.toml for an n × n lattice with the treatment t; the
// inclusion's (or cell's) D in lattice units, D_out = Dout.
std::vector<std::string> scene_overrides(int n, InterfaceTreatment t, double Din, double Dout, long steps) {
  return {set("domain.size_um", double(n), double(n)), set("run.steps", steps),
          set("transport.interface", std::string(interface_name(t))), set("species[0].diffusivity_um2_s", Dout),
          set("species[0].cell_diffusivity_um2_s", Din)};
}

}  // namespace

double biconcave_steady_mean(double h_um, InterfaceTreatment t) {
  const int n = static_cast<int>(std::lround(12.0 / h_um));
  const double Dout = 0.5, Din = Dout * 950.0 / 2800.0;
  // q L²/D_out fixed (L = n nodes): the steady C is the same at every h
  const double q0 = Dout / (static_cast<double>(n) * n);
  // 25 e-foldings of the box's slowest mode (n²/(2π² D_out) steps) from C = 0
  auto set_up = scene_overrides(n, t, Din, Dout, std::lround(25.0 * n * n / (2.0 * kPi * kPi * Dout)));
  // the cell in lattice units: biconcave(800, 3.91 µm / h) at the box centre, held at 0 all round
  set_up.push_back(set("cells[0].shape", std::string("\"biconcave\"")));
  set_up.push_back(set("cells[0].radius_um", 3.91 / h_um));
  set_up.push_back(set("cells[0].center_um", 0.5 * n, 0.5 * n));
  set_up.push_back(set("cells[0].markers", 800L));
  hold_all_sides(set_up, 0.0);
  std::vector<transport::AreaFraction> phi;
  const auto configure = [&](sim::Simulation& s) {  // a uniform source over the cell (φ q0 at cut nodes)
    phi = transport::area_fractions(s.setup().membrane->cells.at(0).shape, n, n);
    auto q = s.transport()->base_source(0);
    for (const auto& c : phi) q[c.node] = c.phi * q0;
    s.transport()->initialize(0, std::vector<double>(static_cast<std::size_t>(n) * n, 0.0));
  };
  const auto run = run_transport(case_scene("verification/transport/curved_interface.toml", set_up),
                                 "verification.transport_curved_interface",
                                 "biconcave_" + fmt_h(h_um) + "_" + std::to_string(static_cast<int>(t)), "C", configure);
  double m = 0.0, w = 0.0;
  for (const auto& c : phi) {
    m += c.phi * run.C[c.node];  // the readout is Ĉ (eq T7)
    w += c.phi;
  }
  return m / w;
}

InclusionRun run_inclusion(const Inclusion& p, int n, InterfaceTreatment t, double D_out_lattice) {
  Stopwatch clock;
  const double h = 2.0 / n;
  const double scale_D = D_out_lattice / p.D_out;  // physical → lattice D
  const Grid grid{n, n};
  const double Din = p.D_in * scale_D, Dout = D_out_lattice;
  // Slowest modes: the box's, e-folding ≤ n²/(π² D_out) steps (one pair of sides held), and the
  // inclusion's, (a/h)²/(2.405² D_in) (first zero of J0): 14 e-foldings of the slower, from the
  // exact field (only the discretisation error has to settle: e^−14 ≈ 1e−6 of it is left).
  const double box = n * n / (kPi * kPi * Dout), inner = (p.a / h) * (p.a / h) / (2.405 * 2.405 * Din);
  const long steps = std::lround(14.0 * std::max(box, inner));
  auto set_up = scene_overrides(n, t, Din, Dout, steps);
  // The inclusion as a fine polygon in lattice units (node (i, j) owns [i, i+1] × [j, j+1]).
  set_up.push_back(set("cells[0].radius_um", p.a / h));
  set_up.push_back(set("cells[0].center_um", 0.5 * n, 0.5 * n));
  // The dipole's sides ∓G, shifted by +G (held values >= 0); the problem is linear, so the field
  // is the exact one + G (subtracted below).
  const double shift = p.problem == InclusionProblem::dipole ? p.G : 0.0;
  if (p.problem == InclusionProblem::dipole) {
    for (const auto& [side, value] : {std::pair{"left", -p.G + shift}, std::pair{"right", p.G + shift}})
      set_up.push_back(set(std::string("species[0].") + side + "_value", value));
  } else {
    hold_all_sides(set_up, p.C_b);
  }
  // Lattice source: amount per node per step = (physical source × lattice time / physical time);
  // with lattice D = scale_D × D, one lattice time unit is scale_D physical units per h².
  // Node sources: q0 over the inside part (φ q0 at cut nodes), the blend ring's pointwise.
  std::vector<double> phi(grid.size(), 0.0), exact(grid.size()), start(grid.size());
  const double q_scale = scale_D * h * h;  // lattice q = physical q × Δt, Δt = scale_D h² (C keeps its unit)
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::size_t k = grid.index(i, j);
      const double x = -1.0 + (i + 0.5) * h, y = -1.0 + (j + 0.5) * h;
      exact[k] = p.concentration(x, y);
      start[k] = exact[k] + shift;
    }
  const auto configure = [&](sim::Simulation& s) {
    for (const auto& c : transport::area_fractions(s.setup().membrane->cells.at(0).shape, n, n)) phi[c.node] = c.phi;
    auto q = s.transport()->base_source(0);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t k = grid.index(i, j);
        const double x = -1.0 + (i + 0.5) * h, y = -1.0 + (j + 0.5) * h;
        const double r = std::hypot(x, y);
        double src = 0.0;
        if (p.problem == InclusionProblem::radial && r < p.R1) {
          src = phi[k] * p.q0;  // exact cell average: q0 on the inside part, 0 outside (r < R1)
        } else {
          src = p.source(x, y);
        }
        q[k] = src * q_scale;
      }
    s.transport()->initialize(0, start);
  };
  const std::string label = std::string(p.problem == InclusionProblem::radial ? "radial_" : "dipole_") +
                            std::to_string(static_cast<int>(t)) + "_n" + std::to_string(n);
  const auto run = run_transport(case_scene("verification/transport/curved_interface.toml", set_up),
                                 "verification.transport_curved_interface", label, "C", configure);
  InclusionRun r;
  r.n = n;
  r.steps = run.steps;
  r.worst_mass_residual = run.worst_mass_residual;
  r.scene_text = run.scene_text;
  double s2 = 0.0, cut2 = 0.0, mean = 0.0, wsum = 0.0;
  long ncut = 0;
  for (std::size_t k = 0; k < grid.size(); ++k) {
    const double e = (run.C[k] - shift - exact[k]) / p.scale();  // the readout is Ĉ (eq T7)
    const double x = -1.0 + (static_cast<double>(k % n) + 0.5) * h, y = -1.0 + (static_cast<double>(k / n) + 0.5) * h;
    const double d = std::hypot(x, y) - p.a;  // signed distance to the interface
    if (std::fabs(d) > 0.1) r.error_bulk = std::max(r.error_bulk, std::fabs(e));
    if (d < -0.1) r.error_bulk_in = std::max(r.error_bulk_in, std::fabs(e));
    s2 += e * e;
    r.error_max = std::max(r.error_max, std::fabs(e));
    if (phi[k] > 0.0 && phi[k] < 1.0) {
      cut2 += e * e;
      ++ncut;
    }
    mean += phi[k] * e;
    wsum += phi[k];
  }
  r.error_l2 = std::sqrt(s2 / static_cast<double>(grid.size()));
  r.error_cut = std::sqrt(cut2 / static_cast<double>(std::max(1L, ncut)));
  r.error_mean = std::fabs(mean / wsum);
  r.wall_s = clock.seconds();
  return r;
}

}  // namespace erythro::vv
