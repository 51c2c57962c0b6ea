// Cases verification.suspension_einstein (full) and verification.suspension_einstein_ci (CI):
// the 2D Einstein coefficient of a dilute suspension (issue 19 item 5).
//
// Requirement: a stiff circular capsule (Ca = μγ̇a/E_S = 0.004, standing for a rigid disk; 2D
// capsules deform readily, so it still takes D = 0.13, the reference_data/capsule_bim value) on
// the centreline of a simple shear, periodic along the flow (a regular dilute suspension at
// φ = πa²/(L H) = 0.0098), raises the viscosity to 1 + [η]φ with the 2D Einstein coefficient
// [η] = 2 within 10 %, in the lattice limit; a deformable capsule (Ca = 0.1) raises it less.
// Reference: [η] = (n + 2)/2 in n dimensions for rigid spheres / disks (Einstein 1906 for
// n = 3; Brady 1984, Int. J. Multiphase Flow 10:113, for n = 2): a torque-free rigid disk in a
// linear flow carries the stresslet S = 4πμa²E per unit length.
// Measure: the steady mean wall shear stress over μγ̇ (shear_relative_viscosity, docs/model.md
// eq 12.5): one disk on the centreline spins in place, so the flow becomes steady (no time
// average of colliding particles) and the last strain unit's mean is asserted steady.
// Convergence: the immersed boundary leaves the disk a smaller hydrodynamic radius, a − δh
// with δ ≈ 1.4 measured (the membrane's forces spread over ±2h), so [η](h) = [η]∞ (1 − δh/a)²:
// √[η] is linear in h/a. Three resolutions a/h = 8, 10, 12.5 fit it by least squares; the fit's
// residual is the asymptotic-range check, and [η]∞ is asserted. docs/verification-suspension.md,
// "Dilute suspension: the Einstein coefficient".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/case_support.hpp"
#include "common/concurrent_runs.hpp"
#include "common/convergence.hpp"
#include "common/scene_case.hpp"
#include "geometry/polygon.hpp"

using namespace erythro;

namespace {

constexpr const char* kScene = "verification/suspension/einstein_shear.toml";
constexpr double kRadiusUm = 3.0, kWidthUm = 48.0, kHeightUm = 60.0;
constexpr double kStepsPerStrainAt0p3 = 3000.0;  // τ = 1.5, γ̇a²/ν = 0.1 at h = 0.3 µm
constexpr double kStrainUnits = 8.0;             // the flow is steady from about 6 (measured)
constexpr double kEinstein = 2.0;
constexpr double kTolerance = 0.10;  // issue 19 item 5
// Stiff: Ca = 0.004 (the explicit membrane update allows 0.0028 at a/h = 10; 0.004 keeps
// Π_T ≤ 1.04 at a/h = 8); deformable: Ca = 0.1.
constexpr double kStiffCa = 0.004, kDeformableCa = 0.1;

struct Level {
  double a_over_h = 0.0, Ca = 0.0;
  double eta = 0.0;          // mean shear_relative_viscosity over the last strain unit
  double eta_before = 0.0;   // … over the one before (steadiness)
  double phi = 0.0;          // the polygon's area / (L H)
  double taylor_deformation = 0.0;  // at the end
  double max_area_change = 0.0, mass_change = 0.0, wall_s = 0.0;
  std::string scene_text;
  double intrinsic() const { return (eta - 1.0) / phi; }
};

// E_S = μγ̇a/Ca in dyn/cm for the scene's plasma (1.2 cP) and γ̇ (0.1 ν/a², ν = 1.2 cP/1025 kg/m³).
double shear_modulus_dyn_cm(double Ca) {
  const double mu = 1.2e-3, nu = mu / 1025.0, a = kRadiusUm * 1e-6;
  return mu * (0.1 * nu / (a * a)) * a / Ca * 1e3;
}

Level run_level(const std::string& case_name, double a_over_h, double Ca) {
  const double h = kRadiusUm / a_over_h;
  const double per_strain = kStepsPerStrainAt0p3 * (0.3 / h) * (0.3 / h);  // Δt ∝ h² at fixed τ
  const long steps = std::lround(kStrainUnits * per_strain);
  const std::vector<std::string> o = {vv::set("domain.spacing_um", h),
                                      vv::set("domain.size_um", kWidthUm, kHeightUm),
                                      vv::set("cells[0].center_um", 0.5 * kWidthUm, 0.5 * kHeightUm),
                                      vv::set("run.steps", steps),
                                      vv::set("output.diagnostics_interval_steps", std::lround(per_strain / 20.0)),
                                      vv::set("membrane.shear_modulus_dyn_cm", shear_modulus_dyn_cm(Ca))};
  char label[48];
  std::snprintf(label, sizeof label, "a_h%g_Ca%g", a_over_h, Ca);
  const vv::CaseRun r = vv::run_case_scene(vv::case_scene(kScene, o), case_name, label);
  if (!r.ok()) throw std::runtime_error(std::string(label) + ": " + r.summary.diagnosis);
  Level L;
  L.a_over_h = a_over_h;
  L.Ca = Ca;
  const std::vector<double>& step = r.file.series("step");
  const std::vector<double>& eta = r.file.series("shear_relative_viscosity");
  double sum[2] = {0.0, 0.0};
  int count[2] = {0, 0};
  for (std::size_t k = 0; k < step.size(); ++k) {
    const double strain = step[k] / per_strain;
    const int unit = strain > kStrainUnits - 1.0 ? 1 : strain > kStrainUnits - 2.0 ? 0 : -1;
    if (unit < 0) continue;
    sum[unit] += eta[k];
    ++count[unit];
  }
  L.eta_before = sum[0] / count[0];
  L.eta = sum[1] / count[1];
  const geometry::Polygon& cell = r.setup.membrane->cells.at(0).shape;
  L.phi = std::abs(geometry::signed_area(cell)) * h * h / (kWidthUm * kHeightUm);
  L.max_area_change = r.file.series("cells_max_area_change").back();
  L.taylor_deformation = r.file.series("cell_0_taylor_deformation").back();
  const std::vector<double>& mass = r.file.series("total_mass_kg_per_m");
  L.mass_change = std::abs(mass.back() / mass.front() - 1.0);
  L.wall_s = r.wall_time_s;
  L.scene_text = r.file.scene_text();
  return L;
}

void describe(io::ResultRecord& record) {
  record.set_requirement(
      "A stiff circular capsule (Ca = 0.004, a rigid disk) on the centreline of a simple shear, periodic along the "
      "flow (a dilute regular suspension, phi = 0.0098), raises the viscosity to 1 + [eta] phi with the 2D Einstein "
      "coefficient [eta] = 2 within 10 % in the lattice limit (three resolutions; least squares; asymptotic-range "
      "check; the stiff capsule still deforms to D = 0.13, which with the walls at 10 a bounds the agreement to a few "
      "per cent); a deformable capsule (Ca = 0.1, D = 0.35) raises it less; each run steady, area within 1 %, mass "
      "conserved.");
  record.set_reference(
      "[eta] = (n + 2)/2 for rigid particles in n dimensions (Einstein 1906, n = 3; Brady 1984, Int. J. Multiphase "
      "Flow 10:113, n = 2): a torque-free rigid disk carries the stresslet 4 pi mu a^2 E per unit length.");
  record.set_parameter("geometry", "one circle of radius 3 um (90-140 markers) at the centre of a 48 x 60 um box, walls "
                                   "at -+U at the bottom and top, periodic in x; H = 20 a, L = 16 a");
  record.set_parameter("flow", "gamma-dot a^2 / nu = 0.1, tau = 1.5, plasma 1.2 cP; neo-Hookean membrane, cosine4 kernel, "
                               "viscosity ratio 1, no repulsion (the cell stays on the centreline)");
  record.set_parameter("measure", "mean of shear_relative_viscosity (wall stress over mu gamma-dot, docs/model.md eq "
                                  "12.5) over the last of 8 strain units");
}

// √[η] = α + β (h/a) by least squares over the levels: α² the lattice limit, δ = −β/α the radius
// deficit in h; `residual` the largest |√[η] − fit| / α (the asymptotic-range check).
struct LimitFit {
  double alpha = 0.0, beta = 0.0, residual = 0.0;
  double limit() const { return alpha * alpha; }
};
LimitFit fit_limit(const std::vector<Level>& levels) {
  std::vector<double> x, y;
  for (const Level& L : levels) {
    x.push_back(1.0 / L.a_over_h);
    y.push_back(std::sqrt(L.intrinsic()));
  }
  LimitFit f;
  f.beta = vv::least_squares_slope(x, y);
  f.alpha = (std::accumulate(y.begin(), y.end(), 0.0) - f.beta * std::accumulate(x.begin(), x.end(), 0.0)) /
            static_cast<double>(x.size());
  for (const Level& L : levels)
    f.residual = std::max(f.residual, std::abs(std::sqrt(L.intrinsic()) - (f.alpha + f.beta / L.a_over_h)) / f.alpha);
  return f;
}

io::Series sqrt_fit_series(const std::string& which, const std::vector<Level>& levels, const LimitFit& f) {
  io::Series s{"sqrt([eta]) against h/a, " + which, "sqrt([eta]) and its least-squares line alpha + beta h/a "
               "(alpha^2 = the lattice limit), " + which, "h/a", "sqrt([eta])", {}, {}, {}};
  const double alpha = f.alpha, beta = f.beta;
  for (const Level& L : levels) {
    s.x.push_back(1.0 / L.a_over_h);
    s.y.push_back(std::sqrt(L.intrinsic()));
    s.y_reference.push_back(alpha + beta / L.a_over_h);
  }
  return s;
}

void add_run(io::ResultRecord& record, const Level& L) {
  const double eta = L.intrinsic();
  record.add_run({{"a_over_h", L.a_over_h},
                  {"Ca", L.Ca},
                  {"phi", L.phi},
                  {"relative_viscosity", L.eta},
                  {"intrinsic_viscosity", eta},
                  {"radius_deficit_h", (1.0 - std::sqrt(eta / kEinstein)) * L.a_over_h},
                  {"taylor_deformation", L.taylor_deformation},
                  {"last_unit_change", L.eta - L.eta_before},
                  {"max_area_change", L.max_area_change},
                  {"mass_change", L.mass_change},
                  {"wall_time_s", L.wall_s},
                  {"error", std::abs(eta - kEinstein) / kEinstein}},
                 L.scene_text);
}

void add_run_metrics(io::ResultRecord& record, const Level& L) {
  char tag[32];
  std::snprintf(tag, sizeof tag, "a_h%g_Ca%g", L.a_over_h, L.Ca);
  record.add_metric({std::string("steady_") + tag, "|mean over the last strain unit - the unit before| of the relative "
                     "viscosity", "", std::abs(L.eta - L.eta_before), 0.02 * kEinstein * L.phi, 0.0,
                     io::Comparison::at_most, "steady to 2 % of the disk's contribution [eta] phi ~ 0.02 (measured "
                     "3e-5 to 5e-5)"});
  record.add_metric({std::string("area_change_") + tag, "largest |A/A0 - 1| over the run", "", L.max_area_change, 0.01,
                     0.0, io::Comparison::at_most, "issue 19 item 6: no leak, the area within 1 %"});
  record.add_metric({std::string("mass_change_") + tag, "|M(end)/M(0) - 1| of the fluid", "", L.mass_change, 1e-12,
                     0.0, io::Comparison::at_most, "the step conserves mass exactly (round-off only)"});
}

}  // namespace

TEST(SuspensionEinstein, CiSubset) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.suspension_einstein_ci", "suspension");
  describe(record);
  record.set_requirement("CI guard of verification.suspension_einstein at a/h = 8: the stiff capsule's [eta] where "
                         "the radius deficit of the immersed boundary puts it (1.36 +- 0.1), the flow steady, the "
                         "area within 1 %, mass conserved.");
  const Level L = run_level(record.case_name(), 8.0, kStiffCa);
  add_run(record, L);
  add_run_metrics(record, L);
  // At a/h = 8 the deficit of ≈ 1.4 h leaves (1 − 1.4/8)² = 0.68 of [η]: 1.36 expected.
  record.add_metric({"intrinsic_viscosity_a_h8", "[eta] = (eta_rel - 1)/phi at a/h = 8", "", L.intrinsic(), 1.36, 0.1,
                     io::Comparison::absolute, "CI regression guard at the coarse lattice (1.36 measured when written; "
                     "the lattice limit is asserted by verification.suspension_einstein)"});
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  for (const auto& m : record.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}

TEST(SuspensionEinstein, ThreeResolutions) {
  vv::Stopwatch total;
  io::ResultRecord record("verification.suspension_einstein", "suspension");
  describe(record);
  const std::string name = record.case_name();
  const std::vector<double> a_over_h{8.0, 10.0, 12.5};
  std::vector<Level> stiff(a_over_h.size()), soft(a_over_h.size());
  std::vector<std::function<void()>> jobs;
  for (std::size_t i = 0; i < a_over_h.size(); ++i) {
    jobs.push_back([&, i] { stiff[i] = run_level(name, a_over_h[i], kStiffCa); });
    jobs.push_back([&, i] { soft[i] = run_level(name, a_over_h[i], kDeformableCa); });
  }
  vv::run_concurrently(jobs);
  const LimitFit fs = fit_limit(stiff), fd = fit_limit(soft);
  for (const std::vector<Level>* set : {&stiff, &soft})
    for (const Level& L : *set) {
      add_run(record, L);
      add_run_metrics(record, L);
    }
  record.set_parameter("fit_stiff_alpha", fs.alpha);
  record.set_parameter("fit_stiff_radius_deficit_h", -fs.beta / fs.alpha);
  record.set_parameter("fit_deformable_alpha", fd.alpha);
  record.set_parameter("fit_deformable_radius_deficit_h", -fd.beta / fd.alpha);
  record.add_metric({"intrinsic_viscosity_limit", "[eta] of the stiff capsule in the lattice limit: alpha^2 of the "
                     "least-squares line sqrt([eta]) = alpha + beta h/a through a/h = 8, 10, 12.5", "", fs.limit(),
                     kEinstein, kTolerance, io::Comparison::relative, "issue 19 item 5: the 2D Einstein coefficient "
                     "within 10 % (the walls at 10 a and the images at 16 a change it by a few per cent at most)"});
  record.add_metric({"asymptotic_range", "max |sqrt([eta]) - fit| / alpha over the three levels, stiff capsule", "",
                     fs.residual, 0.01, 0.0, io::Comparison::at_most, "the levels lie on the first-order line (a "
                     "constant hydrodynamic radius deficit in h): the extrapolation is in its asymptotic range"});
  record.add_metric({"intrinsic_viscosity_finest", "[eta] of the stiff capsule at a/h = 12.5 (no extrapolation)", "",
                     stiff.back().intrinsic(), -std::numeric_limits<double>::infinity(), 0.0, io::Comparison::at_least,
                     "informative: the immersed boundary's radius deficit lowers the raw value"});
  record.add_metric({"deformable_lowers_viscosity", "[eta](Ca = 0.1) / [eta](Ca = 0.004), both in the lattice limit",
                     "", fd.limit() / fs.limit(), 0.98, 0.0, io::Comparison::at_most,
                     "issue 19 item 5: a deformable capsule aligns with the flow and tank-treads, raising the "
                     "viscosity less than a rigid disk (by more than 2 %, beyond the fits' residuals)"});
  record.add_metric({"asymptotic_range_deformable", "max |sqrt([eta]) - fit| / alpha, deformable capsule", "",
                     fd.residual, 0.01, 0.0, io::Comparison::at_most, "as for the stiff capsule"});
  record.add_series(sqrt_fit_series("Ca = 0.004", stiff, fs));
  record.add_series(sqrt_fit_series("Ca = 0.1", soft, fd));
  record.set_wall_time(total.seconds());
  for (const auto* set : {&stiff, &soft}) {
    const LimitFit f = fit_limit(*set);
    std::printf("Ca %g [eta]: %.4f %.4f %.4f -> limit %.4f (deficit %.3f h, residual %.2e), D %.4f\n", set->front().Ca,
                (*set)[0].intrinsic(), (*set)[1].intrinsic(), (*set)[2].intrinsic(), f.limit(), -f.beta / f.alpha,
                f.residual, set->back().taylor_deformation);
  }
  record.write_to_results_dir();
  for (const auto& m : record.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}
