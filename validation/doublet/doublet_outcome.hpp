#pragma once
// Classification of a doublet run and the tumbling periods (issue 6 items 5–7).
#include <string>

#include "doublet_shear_run.hpp"

namespace erythro::vv {

// "dissociates": at some sample no marker pair of the two cells is within the Morse
// cut-off (no aggregation force left). "rotates as one": it never dissociated and the
// line of centres turned from +90° through 0° to −90° (half a revolution of the pair).
// "undetermined": neither within the run; "diverged": the run failed.
std::string doublet_outcome(const DoubletShearResult& r);

// Contact mode (thesis §III.2: flat, sigmoid, relaxed sigmoid) from the S amplitude of
// the contact line (pair_contact_sigmoid_um of the pair probe, |c3|, µm) over the aggregated part of the
// run after γ̇t = 1: "flat" if it never exceeds `threshold_um`; "sigmoid" if its mean
// over the last 10 % of that part is ≥ half its maximum; "relaxed sigmoid" if it fell
// below half; "none" without aggregated samples or without any contact (De* = 0).
std::string contact_mode(const DoubletShearResult& r, double threshold_um = 0.1);
double max_sigmoid(const DoubletShearResult& r);
// Mean over the aggregated samples in γ̇t ∈ [from, to] of the smaller cell's relative contact area.
double mean_contact(const DoubletShearResult& r, double from, double to = 1e300);
// Largest |D(t) − D(0)| of cell 0 / cell 1 over the run (Taylor deformation change).
double max_deformation_change(const DoubletShearResult& r, int cell);
double final_sigmoid(const DoubletShearResult& r);

// Jeffery (1922): full period γ̇T = 2π(a/b + b/a) of a rigid ellipse (docs/parameters.md, exact solution E1).
double jeffery_period(double axis_ratio);
// Measured γ̇T from the quadrant θ: 0 → −90° (each quadrant of a Jeffery orbit takes
// T/4 exactly: ∫ over a quadrant of dθ/(a²sin²θ + b²cos²θ) = π/(2ab)); −1 if not reached.
double quadrant_period(const DoubletShearResult& r);

}  // namespace erythro::vv
