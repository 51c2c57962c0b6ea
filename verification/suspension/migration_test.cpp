// Case verification.capsule_migration (issue 19 item 7): one deformable cell in Poiseuille
// flow drifts towards the centreline, faster at higher capillary number.
//
// Requirement: a circular neo-Hookean capsule (R = 3 µm) starting 4 µm below the centreline
// of a 20 µm channel (capsule_migration.toml, run as `erythro run` runs it) drifts towards
// the centreline by more than h/4 at Ca = μγ̇_w R/E_S = 0.05, 0.1 and 0.2, and over the same
// 5 strain units the drift grows with Ca: each doubling of Ca at least 5 % more.
// Reference: the lateral migration of deformable particles in Stokes flow (Coupier et al.
// 2008, Phys Fluids 20:111702, vesicles; Doddi & Bagchi 2008, Int J Multiphase Flow 34:966,
// 2D capsules in Poiseuille flow): the drift comes from the deformation and grows with it;
// a rigid circle does not drift at Re = 0, and the small inertial lift at the channel
// Reynolds number 0.48 (u_max H/ν) is the same for every Ca (and points outwards at 0.4 of
// the half-width from the centre), so only the deformation can
// order the three drifts. The runs are deterministic (no sampling noise): the 5 % margin
// only keeps a coupling that ignores the deformation (three equal drifts) from passing.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "common/case_support.hpp"
#include "common/concurrent_runs.hpp"
#include "common/scene_case.hpp"

using namespace erythro;

TEST(CapsuleMigration, DriftGrowsWithCapillaryNumber) {
  constexpr const char* kScene = "verification/suspension/capsule_migration.toml";
  vv::Stopwatch total;
  io::ResultRecord record("verification.capsule_migration", "suspension");
  record.set_requirement(
      "A circular capsule 4 um below the centreline of a 20 um channel in plane Poiseuille flow drifts towards the "
      "centreline by more than h/4 at Ca = 0.05, 0.1, 0.2 over 5 strain units at the wall, and each doubling of "
      "Ca drifts it at least 5 % further.");
  record.set_reference(
      "Deformability-induced lateral migration in Stokes flow (Coupier et al. 2008 Phys Fluids 20:111702; Doddi & "
      "Bagchi 2008 Int J Multiphase Flow 34:966): the drift comes from the deformation and grows with Ca.");
  const scene::Scene base = vv::case_scene(kScene);
  const double F = base.body_force->density_N_m3[0], H_m = base.domain.size_um[1] * 1e-6;
  const double R_m = base.cells.at(0).radius_um * 1e-6;
  const std::vector<double> capillary{0.05, 0.1, 0.2};
  const auto tag = [](double ca) {  // "Ca0.05"
    char b[32];
    std::snprintf(b, sizeof b, "Ca%.2f", ca);
    return std::string(b);
  };
  const double centreline_um = 0.5 * base.domain.size_um[1];
  const double h_um = base.domain.spacing_um;
  std::vector<vv::CaseRun> runs(capillary.size());
  std::vector<std::function<void()>> jobs;
  for (std::size_t i = 0; i < capillary.size(); ++i) {
    // Ca = μγ̇_w R / E_S with γ̇_w = F H / (2μ): E_S = F H R / (2 Ca), in dyn/cm (1e3 per N/m).
    const double es_dyn_cm = F * H_m * R_m / (2.0 * capillary[i]) * 1e3;
    jobs.push_back([&, i, es_dyn_cm] {
      runs[i] = vv::run_case_scene(vv::case_scene(kScene, {vv::set("membrane.shear_modulus_dyn_cm", es_dyn_cm)}),
                                   record.case_name(), tag(capillary[i]));
    });
  }
  vv::run_concurrently(jobs);
  const double y_start = base.cells.at(0).center_um[1];
  std::vector<double> drift(capillary.size());
  for (std::size_t i = 0; i < capillary.size(); ++i) {
    const vv::CaseRun& r = runs[i];
    ASSERT_TRUE(r.ok()) << r.summary.diagnosis;
    drift[i] = r.file.series("cell_0_centroid_y_um").back() - y_start;
    record.add_run({{"Ca", capillary[i]},
                    {"steps", static_cast<double>(r.summary.steps)},
                    {"drift_um", drift[i]},
                    {"taylor_deformation", r.file.series("cell_0_taylor_deformation").back()},
                    {"max_area_change", r.file.series("cells_max_area_change").back()},
                    {"wall_time_s", r.wall_time_s}},
                   r.scene.source_text);
    io::Series s;
    s.name = "centroid_y_" + tag(capillary[i]);
    char title[96];
    std::snprintf(title, sizeof title, "Capsule height, %s (centreline at %g um)", tag(capillary[i]).c_str(),
                  centreline_um);
    s.title = title;
    s.xlabel = "t (ms)";
    s.ylabel = "centroid y (um)";
    const std::vector<double>& t = r.file.series("time_s");
    s.x.reserve(t.size());
    for (double v : t) s.x.push_back(v * 1e3);
    s.y = r.file.series("cell_0_centroid_y_um");
    record.add_series(s);
    record.add_metric({"drift_" + tag(capillary[i]), "drift towards the centreline after 5 strain units", "um",
                       drift[i], 0.25 * h_um, 0.0, io::Comparison::at_least,
                       "the capsule moves towards the centreline by more than a quarter lattice spacing, beyond "
                       "the IB's positional round-off; a capsule that stays put fails"});
  }
  for (std::size_t i = 1; i < capillary.size(); ++i)
    record.add_metric({"drift_ratio_" + tag(capillary[i]),
                       "drift at this Ca over the drift at half of it", "", drift[i] / drift[i - 1], 1.05, 0.0,
                       io::Comparison::at_least,
                       "deterministic runs: a coupling that ignored the deformation would give equal drifts"});
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  for (const auto& m : record.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}
