#pragma once
// The ResultRecord parts every doublet case shares: the mapping of the physical inputs
// to lattice units, the per-run histories (series), the run-table row and the
// run-health metrics.
#include <string>

#include "common/case_support.hpp"
#include "doublet_shear_run.hpp"
#include "io/result_record.hpp"

namespace erythro::vv {


// Case-wide parameters: lattice, mapping and model (from the first run of the case).
void add_mapping(io::ResultRecord& rec, const DoubletShearConfig& c, const DoubletShearResult& r);
// Series of one run: θ, contact area per cell, separation, D per cell (doublet), or θ and
// the axis ratio (single cell), and outline snapshots (first and last).
void add_histories(io::ResultRecord& rec, const std::string& label, const DoubletShearResult& r);
// One /runs row.
void add_row(io::ResultRecord& rec, const std::string& label, const DoubletShearConfig& c, const DoubletShearResult& r);
// Run health: finished without divergence; max |A/A0 − 1| ≤ 0.5 % (the rbc case's bound).
void add_health_metrics(io::ResultRecord& rec, const std::string& label, const DoubletShearResult& r);
// Membrane integrity, marker spacing: the largest marker spacing of the run (h), bounded by an
// upper estimate (largest rest edge × (1 + the largest edge strain)); the metric asserts ≤ h
// (scene::kMaxMarkerSpacing, the scene's default limits.max_marker_spacing).
double max_marker_spacing_h(const DoubletShearConfig& c, const DoubletShearResult& r);
void add_marker_spacing_metric(io::ResultRecord& rec, const std::string& label, const DoubletShearConfig& c,
                               const DoubletShearResult& r);
// One summary line and a coarse history on stdout.
void print_run(const std::string& label, const DoubletShearResult& r);

// The end of every doublet case: the wall time, the record written (its path printed), and
// each metric an EXPECT of the test, so that a failing metric names itself.
void finish_record(io::ResultRecord& rec, double wall_time_s);

}  // namespace erythro::vv
