#pragma once
// Calibration harness: fit parameters p so that a simulated curve y(t; p) matches a
// reference curve (t_k, y_k), k = 1..K (docs/validation-deoxygenation.md, "Calibration").
//
//  misfit: the simulated curve is interpolated linearly onto the reference times;
//          r_k(p) = y_sim(t_k; p) − y_k;  max = max_k |r_k|,  rms = √(Σ r_k² / K).
//  1 parameter : Brent's minimisation (golden section + parabolic steps) on the
//                bracket [lower, upper] (Brent 1973, ch. 5) — converges for any
//                unimodal objective, smooth (rms) or not (max).
//  n parameters: Nelder–Mead on the box (points clamped into the bounds).
//  sensitivity at the optimum: the Jacobian J_ki = ∂r_k/∂p_i by central differences;
//          sensitivity_rms_i = √(Σ_k J_ki² / K) (RMS curve change per unit p_i),
//          sensitivity_max_i = max_k |J_ki|, and the width w_i(δ) = δ / sensitivity_rms_i:
//          the change of p_i that moves the curve by δ (RMS) — a confidence-like width
//          for a curve known to ±δ. The Gauss–Newton standard error
//          √diag(s² (JᵀJ)⁻¹), s² = Σ r²/(K − n), is reported too (valid only for
//          independent random residuals; a model-form misfit is not that).
#include <functional>
#include <string>
#include <vector>

namespace erythro::vv {

struct Curve {
  std::vector<double> t, y;  // t strictly increasing
};

// Linear interpolation of c at t; throws std::invalid_argument outside [t_0, t_last]
// (beyond a relative slack of 1e-12 of the span).
double interpolate(const Curve& c, double t);

struct Misfit {
  double max_abs = 0.0;
  double rms = 0.0;
};

// r_k = interpolate(simulated, t_k) − y_k over every reference point.
std::vector<double> residuals(const Curve& simulated, const Curve& reference);
Misfit curve_misfit(const Curve& simulated, const Curve& reference);

enum class MisfitNorm { max_abs, rms };

struct ParameterBound {
  std::string name;
  double lower = 0.0, upper = 1.0;
  double initial = 0.0;  // start of Nelder–Mead (ignored by Brent); clamped into the bounds
};

struct CalibrationOptions {
  MisfitNorm norm = MisfitNorm::rms;
  double x_tolerance = 1e-5;   // relative to each parameter's range (upper − lower)
  int max_evaluations = 200;
  double fd_relative_step = 1e-3;  // central-difference step for J, relative to the range
  // Optional: called with points the harness is about to evaluate and whose choice does not
  // depend on each other's results (the Jacobian's, Nelder–Mead's first simplex and shrinks,
  // refine_1d's difference pair), so that a model can run them concurrently. The results must
  // not depend on whether or how it is used.
  std::function<void(const std::vector<std::vector<double>>&)> prefetch;
};

struct CalibrationResult {
  std::vector<std::string> names;
  std::vector<double> params;   // fitted values
  Misfit misfit;                // at the fitted values
  double objective = 0.0;       // the minimised norm
  int evaluations = 0;          // model calls during the minimisation
  int sensitivity_evaluations = 0;  // model calls after the minimisation: 1 + 2n (Jacobian)
  bool converged = false;       // tolerance reached within max_evaluations
  std::vector<bool> at_bound;   // fitted value within the tolerance of a bound
  std::vector<std::vector<double>> jacobian;  // [k][i] = ∂r_k/∂p_i
  std::vector<double> sensitivity_rms, sensitivity_max, gn_standard_error;
  // w_i(δ) = δ / sensitivity_rms_i (infinite where the curve does not depend on p_i).
  double width(std::size_t i, double delta) const;
};

using CurveModel = std::function<Curve(const std::vector<double>& params)>;

// One parameter, Brent on [bound.lower, bound.upper].
CalibrationResult calibrate_1d(const CurveModel& model, const Curve& reference, const ParameterBound& bound,
                               const CalibrationOptions& options = {});

// One parameter by continuation from a good start x0 (e.g. the fit of a coarser lattice level):
// Gauss–Newton on the linearised misfit r(x) ≈ r(x_k) + J (x − x_k) (RMS: x − x_k = −J·r/J·J;
// max norm: the exact minimum of the convex piecewise-linear max_k |r_k + J_k d|), J by central
// differences at x0 (± fd_relative_step × range; again around the iterate if it moves further
// than half that step), each iterate run once, until the predicted step is within x_tolerance
// of the range; the iterate stays in [lower, upper]. For a misfit that is nearly linear in x
// over the distance from x0 (a lattice level's shift of a calibrated parameter) this takes 3
// model runs (the pair and one iterate), 2 of them concurrent with options.prefetch, where
// Brent on the same bracket takes 8 + 3 sequential ones; the result is within the tolerance of
// the minimum, as Brent's is (the first step uses r(x0) interpolated from the pair, off by
// O(δ²): the next predicted step then measures how far the iterate is from the minimum).
// options.prefetch also receives each iterate, alone, just before it is run.
CalibrationResult refine_1d(const CurveModel& model, const Curve& reference, const ParameterBound& bound, double x0,
                            const CalibrationOptions& options = {});

// Any number of parameters, Nelder–Mead from the bounds' initial values (initial step
// 10 % of each range). One parameter also works (use calibrate_1d for a bracket).
CalibrationResult calibrate(const CurveModel& model, const Curve& reference, const std::vector<ParameterBound>& bounds,
                            const CalibrationOptions& options = {});

// Brent's minimisation of f on [a, b] to |Δx| ≤ tol (+ round-off); returns x_min.
// evaluations (if given) is incremented per call of f.
double brent_minimize(const std::function<double(double)>& f, double a, double b, double tol, int max_evaluations,
                      int* evaluations = nullptr, bool* converged = nullptr);

}  // namespace erythro::vv
