#pragma once
// Two cells in still fluid with Morse aggregation: the scene doublet.toml (the solver's
// IB cycle with the aggregation forces added to the membrane forces, sim::CellPhysics),
// set for a lattice set-up by overrides (common/lattice_inputs.hpp: each value the
// physical number the solver converts to exactly the lattice one) and run as
// `erythro run` does. The markers are copied in memory every sample_every steps (lattice
// units, a stage of the case); the gap, drift, rotation and the force balance of the final
// state are computed from them.
#include <string>
#include <vector>

#include "aggregation/morse.hpp"
#include "ib/kernel.hpp"
#include "membrane/membrane_energy.hpp"

namespace erythro::vv {

struct DoubletSetup {
  int nx = 96, ny = 64;           // periodic box
  double tau = 1.0;               // BGK
  ib::KernelType kernel = ib::KernelType::cosine4;
  double radius = 10.0;           // circles
  int markers = 80;
  membrane::MembraneModel model;  // rest shape = the initial circle
  aggregation::MorseParameters morse;
  double initial_gap = 4.0;       // wall-to-wall, along x
  double y0 = 31.3;               // both centres at this height
  double angle0 = 0.0, angle1 = 0.0;  // rotations of the two marker sets
  long steps = 20000;
  long sample_every = 100;
};

struct DoubletResult {
  std::vector<double> step, gap;  // time series (every sample_every steps)
  double final_gap = 0.0;         // |C1 − C2| − R1 − R2 at the end (C: marker mean, R: mean radius)
  double gap_change_last_10pc = 0.0;  // |gap(T) − gap(0.9 T)|: settled when small
  double com_drift = 0.0;         // |displacement of (C1 + C2)/2| over the run
  double max_deformation = 0.0;   // max over markers |r_m − R| at the end (r_m from the centroid)
  double contact_area0 = 0.0, contact_area1 = 0.0;  // relative contact area at the end
  double discrete_rigid_gap = 0.0;  // gap where the discrete Morse force on the INITIAL rigid polygons vanishes
  double rotation_arc0 = 0.0, rotation_arc1 = 0.0;  // R·Δθ of marker 0 about its cell's centroid (signed)
  double balance_shift = 0.0;  // rigid shift of cell 1 along the centre line at which the net Morse force
                               // between the FINAL shapes vanishes (0 for a state at rest)
  std::string scene_text;         // the scene as run
  double wall_time_s = 0.0;
  long steps_done = 0;
  bool diverged = false;
};

// Runs into <results>/runs/<case_name>/<label>.
DoubletResult run_doublet(const DoubletSetup& s, const std::string& case_name, const std::string& label);

}  // namespace erythro::vv
