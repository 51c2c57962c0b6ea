#pragma once
// One run of the inflated-circle (Laplace) set-up: a circular membrane of radius R
// whose rest radius is R/1.05 (pre-stressed, λ = 1.05), in a periodic 4R × 4R box
// of fluid at rest, until the pressure field is steady (50 R² steps): the scene
// inflated_circle.toml set by overrides and run as `erythro run` does
// (membrane_scene.hpp); the pressure from the final density field (lattice units,
// sim::FieldsRecorder), R and T from the final markers.
#include <string>

#include "ib/kernel.hpp"

namespace erythro::vv {

struct LaplaceConfig {
  ib::KernelType kernel = ib::KernelType::peskin4;
  double radius = 8.0;         // R (lattice); markers 8R (spacing ≈ 0.785 h)
  double stretch = 1.05;       // R / R_rest
  double modulus = 0.02;       // neo-Hookean E_s (lattice)
  double tau = 1.0;
};

struct LaplaceResult {
  std::string scene_text;  // the scene as run
  bool diverged = false;
  long steps = 0;
  double radius = 0;    // mean marker distance to the centroid at the end
  double stretch = 0;   // polygon perimeter / rest perimeter at the end
  double tension = 0;   // T(stretch)
  double dp = 0;        // c_s²(ρ_inside − ρ_outside)
  double dp_exact = 0;  // T / radius
  double error = 0;     // dp / dp_exact − 1
  double polygon_term = 0;  // −π²/(6n²): the n-gon's force deficit, sin(π/n)/(π/n) − 1
  double area_loss = 0;     // 1 − A_end / A_start (IB leakage)
  double max_fluid_speed = 0;  // spurious currents at the end
  double wall_time_s = 0;
};

LaplaceResult run_laplace(const LaplaceConfig& c, const std::string& case_name);

}  // namespace erythro::vv
