#pragma once
// Overrides of the fluid family's scenes (channel.toml, periodic_box.toml, ...) stated in
// lattice units, as the cases' set-ups are: h = 1 µm in every scene, so a node count is
// a size in µm; τ, velocities, forces and frequencies are set to the physical values whose
// conversion gives the lattice value bit for bit (vv::exact_input, common/lattice_inputs.hpp).
// The scenes' h, Δt and ρ make every conversion factor a power of two, so those values exist
// for velocities and forces; a note on stderr says when one does not (the run then differs
// from the case's set-up by that round-off).
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "common/scene_file.hpp"
#include "fluid/collision.hpp"

namespace erythro::vv {

// domain.size_um = [nx, ny] (h = 1 µm).
std::string set_grid(int nx, int ny);
// fluid.collision = "bgk" | "trt" | "regularized".
std::string set_collision(fluid::CollisionModel model);
// fluid.viscosity_cP giving the relaxation time `tau` bit for bit at the scene's h and Δt
// (time.step_s): τ = ½ + 3νΔt/h², ν = μ/ρ (docs/scenes.md "Unit conversion").
std::string set_tau(const SceneFile& file, const std::vector<std::string>& overrides, double tau);

using LatticeVector = std::function<std::array<double, 2>(const scene::LatticeSetup&)>;
using LatticeScalar = std::function<double(const scene::LatticeSetup&)>;

// "key=[x, y]" whose lattice value `lattice_of` is `target`, component by component;
// physical ≈ lattice × per_lattice(setup) is the first guess (searched ±64 ulps).
std::string set_exact(const SceneFile& file, const std::vector<std::string>& overrides, const std::string& key,
                      std::array<double, 2> target, const LatticeScalar& per_lattice, const LatticeVector& lattice_of);
// "key=x" for a number, from a first guess `rough` within a few ulps.
std::string set_exact(const SceneFile& file, const std::vector<std::string>& overrides, const std::string& key,
                      double target, double rough, const LatticeScalar& lattice_of);

// Conversion factors physical/lattice of a set-up (first guesses for set_exact).
double um_s_per_lattice(const scene::LatticeSetup& setup);  // velocity
double N_m3_per_lattice(const scene::LatticeSetup& setup);  // force density

// Ready-made: the uniform body force, the top wall's velocity, the initial velocity.
std::string set_body_force(const SceneFile& file, const std::vector<std::string>& overrides,
                           std::array<double, 2> force);
std::string set_top_wall_velocity(const SceneFile& file, const std::vector<std::string>& overrides, double ux);
std::string set_initial_velocity(const SceneFile& file, const std::vector<std::string>& overrides,
                                 std::array<double, 2> u);

}  // namespace erythro::vv
