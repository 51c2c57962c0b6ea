#pragma once
// A scene as the user wrote it: physical units throughout (µm, s, cP, kg/m³, N/m³,
// µm/s). Produced by scene_parser (TOML), consumed by units.hpp, which derives the
// lattice parameters and rejects impossible set-ups. Keys: docs/scenes.md.
//
// A scene declares only the modules it needs; an absent module is std::nullopt and
// nothing is allocated for it.
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace erythro::scene {

struct DomainSpec {
  std::array<double, 2> size_um{0.0, 0.0};  // [domain] size_um = [Lx, Ly]
  double spacing_um = 0.0;                  // [domain] spacing_um = h
};

struct TimeSpec {
  // Exactly one of the two is given: the time step, or the relaxation time from
  // which Δt = (τ − ½) h² / (3ν) follows.
  std::optional<double> step_s;  // [time] step_s
  std::optional<double> tau;     // [time] tau
};

struct FluidSpec {
  double density_kg_m3 = 1025.0;  // [fluid] density_kg_m3 (plasma, parameters.md)
  double viscosity_cP = 1.2;      // [fluid] viscosity_cP (plasma, thesis §II.4)
  std::string collision = "bgk";  // [fluid] collision = "bgk" | "trt"
  double trt_magic = 3.0 / 16.0;  // [fluid] trt_magic (Λ)
};

struct SideSpec {
  std::string type = "periodic";                 // "periodic" | "wall" | "moving_wall"
  std::array<double, 2> velocity_um_s{0.0, 0.0};  // moving_wall only
};

struct BoundarySpec {
  SideSpec left, right, bottom, top;  // [boundaries.left] type = ..., velocity_um_s = [...]
};

struct BodyForceSpec {
  std::array<double, 2> density_N_m3{0.0, 0.0};  // [body_force] density_N_m3 (= Pa/m)
  double frequency_Hz = 0.0;                      // F(t) = F0 cos(2π f t + phase); 0 = steady
  double phase_rad = 0.0;
};

struct InitialSpec {
  // "rest" | "uniform" | "shear" (linear profile between the bottom and top walls'
  // velocities) | "taylor_green" (u = −U cos(kx x) sin(ky y), v = U (kx/ky) sin(kx x) cos(ky y),
  // wavelengths = domain size; see simulation.cpp)
  std::string type = "rest";
  std::array<double, 2> velocity_um_s{0.0, 0.0};  // uniform: the velocity; taylor_green: [U, 0]
};

struct SteadyStateSpec {
  double tolerance = 1e-10;     // stop when max|u^{n} − u^{n−k}| / max|u^n| < tolerance
  long check_interval_steps = 100;
};

struct RunSpec {
  // Exactly one of the two.
  std::optional<long> steps;         // [run] steps
  std::optional<double> duration_s;  // [run] duration_s
  std::optional<SteadyStateSpec> steady_state;  // [run.steady_state]
};

struct MonitorSpec {
  long interval_steps = 100;  // [monitor] interval_steps: health check period K
  double max_mach = 0.3;      // [monitor] max_mach: a run whose |u|/c_s exceeds this stops
};

struct OutputSpec {
  long fields_interval_steps = 0;        // 0: only the initial and final states
  long diagnostics_interval_steps = 100;
  std::vector<std::string> fields{"density", "velocity"};  // allowed: density, velocity
};

struct LimitsSpec {
  double min_tau_margin = 0.005;   // reject τ < 0.5 + margin
  double max_mach = 0.1;           // reject a set-up whose expected |u|/c_s exceeds this
  int min_nodes_across_channel = 4;  // reject a wall-bounded direction with fewer nodes
};

struct Scene {
  std::string source_path;  // file the scene came from ("" for programmatic scenes)
  std::string source_text;  // the scene as parsed, after --set overrides (recorded in outputs)
  std::string name;         // [scene] name
  std::string description;  // [scene] description
  DomainSpec domain;
  TimeSpec time;
  FluidSpec fluid;
  BoundarySpec boundaries;
  std::optional<BodyForceSpec> body_force;
  InitialSpec initial;
  RunSpec run;
  MonitorSpec monitor;
  OutputSpec output;
  LimitsSpec limits;
};

}  // namespace erythro::scene
