#include "capsule_run.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/scene_case.hpp"

namespace erythro::vv {

namespace {

// The overrides of capsule.toml for one level, and the lattice shear rate they give.
struct CapsuleSetUp {
  std::vector<std::string> overrides;
  double gamma = 0;  // γ̇ in lattice units
  long markers = 0;
  double a_um = 0, h_um = 0;  // the capsule's radius (capsule.toml) and the spacing a/(a/h)
  double centre_y_um = 0;     // mid-channel
};

CapsuleSetUp capsule_set_up(const CapsuleConfig& c) {
  // The physical set-up of one level: the capsule of capsule.toml (a = 4 µm) in plasma,
  // h = a/(a/h), γ̇ from the particle Reynolds number γ̇a²/ν, E_s from G = μγ̇a/E_s.
  const scene::Scene base = case_scene("validation/capsule/capsule.toml");
  const double mu = base.fluid.viscosity_cP * 1e-3, nu = mu / base.fluid.density_kg_m3;
  const double a_um = base.cells.at(0).radius_um, h_um = a_um / c.radius;
  const int nx = static_cast<int>(std::lround(c.length * c.radius));
  const int ny = static_cast<int>(std::lround(c.height * c.radius));
  const double shear_rate = c.reynolds * nu / (a_um * a_um * 1e-12);  // 1/s
  const double U = 0.5 * shear_rate * ny * h_um;                       // µm/s
  const double Es_dyn_cm = mu * shear_rate * a_um * 1e-6 / c.capillary * 1e3;
  CapsuleSetUp s;
  s.a_um = a_um;
  s.h_um = h_um;
  s.centre_y_um = 0.5 * ny * h_um;
  s.markers = std::lround(c.markers_per_radius * c.radius);
  s.overrides = {set("domain.spacing_um", h_um),
                 set("domain.size_um", nx * h_um, ny * h_um),
                 set("boundaries.bottom.velocity_um_s", -U, 0.0),
                 set("boundaries.top.velocity_um_s", U, 0.0),
                 set("membrane.shear_modulus_dyn_cm", Es_dyn_cm),
                 set("membrane.kernel", "\"" + std::string(ib::to_string(c.kernel)) + "\""),
                 set("membrane.law", "\"" + c.law + "\""),
                 // Centre mid-channel, 0.123 h off the lattice symmetry in x.
                 set("cells[0].center_um", (0.5 * nx + 0.123) * h_um, s.centre_y_um),
                 set("cells[0].markers", s.markers)};
  if (c.area_projection) s.overrides.push_back(set("membrane.area_correction", "\"projection\""));
  // The lattice shear rate through the unit conversion, which also checks the set-up (the
  // membrane's stability limit among others) and throws InputError when `erythro run` would.
  s.gamma = scene::derive_lattice(case_scene("validation/capsule/capsule.toml", s.overrides)).scales.time_s *
            shear_rate;
  return s;
}

}  // namespace

void check_capsule(const CapsuleConfig& c) { capsule_set_up(c); }

CapsuleResult run_capsule(const CapsuleConfig& c, const std::string& case_name, const std::string& label) {
  const CapsuleSetUp s = capsule_set_up(c);
  const double gamma = s.gamma;
  std::vector<std::string> set_up = s.overrides;
  // The run length, sampling (0.1 strain units) and the stop rule (unit means of D, once the
  // strain is min_strain) in steps.
  const long sample_every = std::max(1L, std::lround(0.1 / gamma));
  set_up.push_back(set("run.steps", std::lround(c.max_strain / gamma)));
  set_up.push_back(set("output.diagnostics_interval_steps", sample_every));
  set_up.push_back(set("stop_when[0].change_below", c.steady_drift));
  set_up.push_back(set("stop_when[0].window_steps", 10 * sample_every));
  // The first step at strain ≥ min_strain; γ̇ comes through the unit conversion, so min_strain/γ̇
  // may exceed an integer by round-off (8640.000000001 steps for strain 4 at a/h = 6): not a step more.
  set_up.push_back(set("stop_when[0].min_steps", static_cast<long>(std::ceil(c.min_strain / gamma - 1e-6))));
  CaseRunOptions options;
  options.pictures = c.pictures;
  const CaseRun run = run_case_scene(case_scene("validation/capsule/capsule.toml", set_up), case_name, label, options);

  CapsuleResult r;
  r.scene_text = run.file.scene_text();
  r.pictures = run.pictures;
  r.shear_rate = gamma;
  r.markers = static_cast<int>(s.markers);
  r.steps = run.summary.steps;
  r.wall_time_s = run.wall_time_s;
  r.t_forces = run.file.stage_seconds("membrane_forces");
  r.t_zero = run.file.stage_seconds("force_field_reset");
  r.t_spread = run.file.stage_seconds("spreading");
  r.t_fluid = run.file.stage_seconds("fluid_step");
  r.t_moments = run.file.stage_seconds("interpolation");
  r.t_move = run.file.stage_seconds("marker_advection");
  const auto& step = run.file.series("step");
  const auto& D = run.file.series("cell_0_taylor_deformation");
  const auto& theta = run.file.series("cell_0_orientation_deg");
  const auto& phase = run.file.series("cell_0_marker_phase_deg");
  const auto& area = run.file.series("cell_0_area_change");
  for (std::size_t k = 1; k < step.size(); ++k) {  // every sample after the start
    r.strain_history.push_back(step[k] * gamma);
    r.D_history.push_back(D[k]);
    r.theta_history.push_back(theta[k]);
    r.area_history.push_back(area[k]);
  }
  const std::size_t k = r.D_history.size();
  if (!run.ok() || k < 12) {
    r.diverged = true;
    r.diagnosis = run.ok() ? "fewer than 12 samples" : run.summary.diagnosis;
    return r;
  }
  r.strain = r.strain_history.back();
  r.drift = std::abs(r.D_history[k - 1] - r.D_history[k - 11]);  // 10 samples = 1 strain unit
  // Steady values: means over the last strain unit (10 samples) smooth the marker jitter.
  for (std::size_t i = k - 10; i < k; ++i) {
    r.D += r.D_history[i] / 10.0;
    r.theta_deg += r.theta_history[i] / 10.0;
  }
  if (k >= 20) {
    double before = 0.0;
    for (std::size_t i = k - 20; i < k - 10; ++i) before += r.D_history[i] / 10.0;
    r.D_unit_change = r.D - before;
  }
  // Tank-treading period T: in steady tank-treading a marker at angle φ moves at ω(φ) and
  // the markers (equally spaced in the Lagrangian label) have density ∝ 1/ω(φ), so the
  // mean of ω over all markers is 2π / ∮dφ/ω = 2π/T exactly. The mean marker phase over
  // the last strain unit gives that mean rate (degrees per strain unit).
  const std::size_t last = phase.size() - 1, first = last - 10;
  const double rate = (phase[last] - phase[first]) / ((step[last] - step[first]) * gamma);
  r.tt_period = 360.0 / std::abs(rate);  // in units of 1/γ̇
  r.area_change = run.file.series("cell_0_area_change").back();
  if (run.file.has("cell_0_area_restored")) r.area_restored = run.file.series("cell_0_area_restored").back();
  const double cy_um = run.file.series("cell_0_centroid_y_um").back();
  r.centre_drift = std::abs(cy_um - s.centre_y_um) / s.a_um;
  return r;
}

}  // namespace erythro::vv
