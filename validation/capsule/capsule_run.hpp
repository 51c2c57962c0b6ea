#pragma once
// One run of the capsule-in-shear set-up (validation.capsule_shear): the scene
// capsule.toml (a circular neo-Hookean capsule of radius a = 4 µm, no bending, no
// prestress, no area penalty, centred between two walls moving at ∓U, periodic in x,
// one fluid), set for one level of the study by overrides and run as `erythro run`
// does until the Taylor deformation D is steady or a strain cap is reached
// (capsule.toml's [[stop_when]]).
#include <string>
#include <vector>

#include "ib/kernel.hpp"
#include "io/result_record.hpp"

namespace erythro::vv {

struct CapsuleConfig {
  ib::KernelType kernel = ib::KernelType::cosine4;
  std::string law = "neo_hookean";  // membrane.law: neo_hookean or hookean (same E_s, docs/model.md)
  double radius = 6.0;         // a/h
  double capillary = 0.05;     // G = μγ̇a/E_s
  double reynolds = 0.1;       // particle Reynolds number γ̇a²/ν
  double height = 16.0;        // H/a (wall to wall)
  double length = 16.0;        // L_x/a (periodic)
  double markers_per_radius = 12.0;  // n = round(12 a/h): spacing ≈ 0.52 h at rest
  double max_strain = 12.0;    // cap on γ̇t
  double min_strain = 4.0;     // never stop before this strain
  double steady_drift = 1e-4;  // stop when |ΔD| over the last strain unit is below this
  bool pictures = false;       // keep pictures of the last field output (speed, membrane) for the report
  bool area_projection = false;  // membrane.area_correction = "projection" (docs/model.md eq 3.14)
};

struct CapsuleResult {
  bool diverged = false;
  std::string diagnosis;
  std::string scene_text;  // the scene as run (after overrides)
  long steps = 0;
  double strain = 0;       // γ̇t reached
  double shear_rate = 0;   // γ̇ (lattice)
  int markers = 0;
  double D = 0;            // Taylor deformation, mean over the last strain unit
  double theta_deg = 0;    // inclination of the long axis to the flow, mean over the last strain unit
  double drift = 0;        // |D(end) − D(end − 1 strain unit)| (single samples)
  double D_unit_change = 0;  // D's mean over the last strain unit minus its mean over the unit before
                             // (no samples' jitter; 0 when the run has fewer than two units of samples)
  double tt_period = 0;    // tank-treading period × γ̇ (time for a marker to go once round)
  double area_change = 0;  // A_end/A_0 − 1
  double centre_drift = 0; // |y_c − H/2| / a at the end
  double area_restored = 0;  // with the projection: the area it gave back over the run, over A0
  // Wall time of the stages of the time loop (s): membrane forces, zeroing the force
  // field, spreading, fluid step, support-node velocity, interpolation and marker update.
  double t_forces = 0, t_zero = 0, t_spread = 0, t_fluid = 0, t_moments = 0, t_move = 0, wall_time_s = 0;
  std::vector<double> strain_history, D_history, theta_history, area_history;  // every 0.1 strain unit
  std::vector<io::FieldPicture> pictures;  // CapsuleConfig::pictures: the last field output
};

CapsuleResult run_capsule(const CapsuleConfig& c, const std::string& case_name, const std::string& label);

// Builds the level's scene and converts it to lattice units without running it: throws
// InputError where run_capsule would (an impossible or unstable set-up), in milliseconds.
void check_capsule(const CapsuleConfig& c);

}  // namespace erythro::vv
