#pragma once
// Transverse dispersion of cells from their trajectories (issue 19 item 3; docs/model.md
// §12, eq 12.4). From the centroid heights y_c(t) of N cells sampled every Δt:
//
//   MSD(τ_k) = ⟨(y_c(t + τ_k) − y_c(t))²⟩ over cells c and time origins t,  τ_k = kΔt
//   α(τ)     = d ln MSD / d ln τ   (local slope: 2 ballistic, 1 diffusive, → 0 confined)
//   D_yy     = slope of the least-squares line MSD = 2 D_yy τ + c over the diffusive window
//
// The diffusive window is the longest run of consecutive lags with |α − 1| ≤ tolerance,
// at least `min_points` lags long; without one, D_yy is not defined (found = false). In a
// channel the walls bound y, so MSD saturates at long lags: the window, when there is one,
// lies between the ballistic start and the confinement.
#include <vector>

namespace erythro::analysis {

struct MsdPoint {
  double lag = 0.0;    // τ (the unit of Δt)
  double msd = 0.0;    // (the unit of y)²
  double slope = 0.0;  // α(τ) by central differences in ln τ (one-sided at the ends)
  long pairs = 0;      // (cell, origin) pairs averaged
};

struct Dispersion {
  std::vector<MsdPoint> msd;
  bool found = false;          // a diffusive window exists
  double lag_from = 0.0, lag_to = 0.0;  // its first and last lag
  double D = 0.0;              // D_yy ((unit of y)² per unit of Δt); 0 when not found
};

struct DispersionOptions {
  double slope_tolerance = 0.2;  // |α − 1| in the window
  int min_points = 4;            // lags in the window
  double max_lag_fraction = 0.5; // lags up to this fraction of the series' length
};

// `y[c]` is cell c's series (all of the same length, uniform Δt = dt > 0). Lags run over
// k = 1, 2, 3, … spaced about 10 per decade up to max_lag_fraction of the length.
// Throws std::invalid_argument on empty or ragged series or dt ≤ 0.
Dispersion transverse_dispersion(const std::vector<std::vector<double>>& y, double dt,
                                 const DispersionOptions& options = {});

// The apparent D_yy at one lag, MSD(τ)/(2τ) at the lag of `d` nearest `lag` (with or without a
// diffusive window: runs compared at the same lag). Throws std::invalid_argument when `d` holds
// no lag.
double dispersion_at_lag(const Dispersion& d, double lag);

}  // namespace erythro::analysis
