#pragma once
// Transverse dispersion across a channel (issue 19 item 8, "D_yy across the channel";
// docs/model.md §12, eq 12.4b): the displacements of the cells over one lag τ = kΔt, sorted
// by the height y_c(t) the cell had at the time origin. For the origins (c, t) whose height
// falls in bin b,
//
//   Δ = y_c(t + τ) − y_c(t),   u_b = ⟨Δ⟩_b / τ,   D_b = (⟨Δ²⟩_b − ⟨Δ⟩_b²) / (2τ)
//
// u_b is the cells' mean lateral drift out of bin b (towards the centre next to a wall: the
// lift), D_b their lateral dispersion about that drift, the second Kramers–Moyal coefficient
// at lag τ. D_b is the local diffusivity only when τ is longer than the time the cells'
// lateral velocity stays correlated and short enough that √(2 D_b τ) stays within the scale
// on which D varies; `profile_lag` picks the lag the whole-channel MSD (eq 12.4) suggests.
#include <vector>

#include "analysis/dispersion.hpp"

namespace erythro::analysis {

struct DispersionBin {
  double y_from = 0.0, y_to = 0.0;  // the bin [y_from, y_to) of origin heights
  long pairs = 0;                   // (cell, origin) pairs whose origin is in the bin
  double drift = 0.0;               // u_b (unit of y per unit of Δt); NaN when pairs = 0
  double D = 0.0;                   // D_b ((unit of y)² per unit of Δt); NaN when pairs < 2
};

struct DispersionProfile {
  double lag = 0.0;  // τ = kΔt
  std::vector<DispersionBin> bins;
};

// eq 12.4b at lag τ = `lag_steps` Δt over `bins` equal bins of [y_from, y_to); origins outside
// are left out. `y[c]` as for transverse_dispersion. Throws std::invalid_argument on empty or
// ragged series, dt ≤ 0, lag_steps < 1 or not below the series' length, bins < 1 or
// y_to ≤ y_from.
DispersionProfile dispersion_across(const std::vector<std::vector<double>>& y, double dt, long lag_steps, double y_from,
                                    double y_to, int bins);

// The lag for eq 12.4b from the whole channel's MSD (eq 12.4): the diffusive window's first lag
// when there is one; else the first lag past the ballistic start, where α has fallen to 1 +
// tolerance; else the longest lag. `d` must hold at least one lag.
double profile_lag(const Dispersion& d, const DispersionOptions& options = {});

}  // namespace erythro::analysis
