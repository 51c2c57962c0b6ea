#include "doublet_run.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "aggregation/cell_contacts.hpp"
#include "aggregation/morse_units.hpp"
#include "common/lattice_inputs.hpp"
#include "common/scene_case.hpp"
#include "geometry/polygon.hpp"
#include "membrane/membrane_units.hpp"
#include "simulation/simulation.hpp"

namespace erythro::vv {

namespace {

constexpr const char* kScene = "verification/aggregation/doublet.toml";

double image(double d, double L) { return d - L * std::round(d / L); }

// Centre (marker mean), mean radius and largest deviation from it of one cell's markers.
struct Shape {
  double cx = 0, cy = 0, R = 0, dev = 0;
};

Shape measure(const geometry::Polygon& p) {
  Shape s;
  const double n = double(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    s.cx += p.x[i] / n;
    s.cy += p.y[i] / n;
  }
  for (std::size_t i = 0; i < p.size(); ++i) s.R += std::hypot(p.x[i] - s.cx, p.y[i] - s.cy) / n;
  for (std::size_t i = 0; i < p.size(); ++i)
    s.dev = std::max(s.dev, std::abs(std::hypot(p.x[i] - s.cx, p.y[i] - s.cy) - s.R));
  return s;
}

// Net Morse force on rigid polygon b, shifted by s along the unit vector e (from a's
// centre to b's), projected on e: > 0 pushes b away from a (repulsion).
double force_along(aggregation::CellContacts& agg, const geometry::Polygon& a, const geometry::Polygon& b,
                   double ex, double ey, double s) {
  std::vector<double> x(a.x), y(a.y);
  for (std::size_t i = 0; i < b.size(); ++i) {
    x.push_back(b.x[i] + s * ex);
    y.push_back(b.y[i] + s * ey);
  }
  const std::vector<std::size_t> off{0, a.size(), a.size() + b.size()};
  std::vector<double> fx(x.size(), 0.0), fy(x.size(), 0.0);
  agg.add_forces(aggregation::MarkerView{x, y, off}, fx, fy);
  double f = 0.0;
  for (std::size_t i = a.size(); i < x.size(); ++i) f += fx[i] * ex + fy[i] * ey;
  return f;
}

// The shift s ∈ (lo, hi) of b along e where that force changes sign from + to −
// (first sign change on a 0.05 grid, then bisection).
double balance_root(aggregation::CellContacts& agg, const geometry::Polygon& a, const geometry::Polygon& b,
                    double ex, double ey, double lo, double hi) {
  double l = lo, h = lo;
  bool found = false;
  for (double s = lo + 0.05; s < hi; s += 0.05) {
    if (force_along(agg, a, b, ex, ey, s) < 0.0) {
      h = s;
      found = true;
      break;
    }
    l = s;
  }
  if (!found) return NAN;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (l + h);
    (force_along(agg, a, b, ex, ey, mid) > 0.0 ? l : h) = mid;
  }
  return 0.5 * (l + h);
}

// Gap where the discrete Morse force between the rigid INITIAL polygons vanishes.
double discrete_rigid_gap(const geometry::Domain& dom, const aggregation::MorseParameters& p, const geometry::Polygon& a,
                          const geometry::Polygon& b, double R) {
  aggregation::CellContacts agg(dom, p);
  const double gap0 = measure(b).cx - measure(a).cx - 2.0 * R;
  return gap0 + balance_root(agg, a, b, 1.0, 0.0, 0.1 * p.r0 - gap0, p.cutoff - gap0);
}

// The overrides of doublet.toml for the lattice set-up `s` (h = the scene's spacing).
std::vector<std::string> overrides(const DoubletSetup& s) {
  const double h_um = case_scene(kScene).domain.spacing_um;
  std::vector<std::string> o = {set("domain.size_um", s.nx * h_um, s.ny * h_um), set("time.tau", s.tau),
                                set("run.steps", s.steps)};
  for (const std::string& m : membrane_overrides(kScene, o, s.kernel, s.model)) o.push_back(m);
  // [aggregation] as the solver converts it (scene/cell_checks.cpp, aggregation/morse_units.hpp).
  const scene::UnitScales u = scene::derive_lattice(case_scene(kScene, o)).scales;
  const membrane::LatticeScales ms{u.length_m, u.time_s, u.density_kg_m3};
  const auto lattice = [&](double De_Pa, double r0_um, double beta_per_um, double cutoff_um) {
    return aggregation::to_lattice({De_Pa, r0_um * 1e-6, beta_per_um * 1e6, cutoff_um * 1e-6}, ms);
  };
  const aggregation::MorseParameters guess = aggregation::to_lattice({1.0, 1e-6, 1e6, 2e-6}, ms);  // unit factors
  const double r0 = exact_input(s.morse.r0 / guess.r0, s.morse.r0, [&](double x) { return lattice(1, x, 1, 2 * x).r0; });
  const double beta = exact_input(s.morse.beta / guess.beta, s.morse.beta,
                                  [&](double x) { return lattice(1, 1, x, 2).beta; });
  const double cutoff = exact_input(s.morse.cutoff / guess.cutoff * 2.0, s.morse.cutoff,
                                    [&](double x) { return lattice(1, x / 2, 1, x).cutoff; });
  const double De = exact_input(s.morse.De / guess.De, s.morse.De, [&](double x) { return lattice(x, 1, 1, 2).De; });
  o.push_back(set("aggregation.pair_density_Pa", De));
  o.push_back(set("aggregation.zero_force_distance_um", r0));
  o.push_back(set("aggregation.decay_per_um", beta));
  o.push_back(set("aggregation.cutoff_um", cutoff));
  // Two circles on the line y = y0, gap initial_gap along x, centred in x.
  const double xm = 0.5 * s.nx, D0 = 2.0 * s.radius + s.initial_gap;
  const double x[2] = {xm - 0.5 * D0, xm + 0.5 * D0}, angle[2] = {s.angle0, s.angle1};
  for (int c = 0; c < 2; ++c) {
    const std::string p = "cells[" + std::to_string(c) + "].";
    o.push_back(set(p + "radius_um", length_um(s.radius, h_um)));
    o.push_back(set(p + "center_um", length_um(x[c], h_um), length_um(s.y0, h_um)));
    o.push_back(angle_override(p + "angle_deg", angle[c]));
    o.push_back(set(p + "markers", long(s.markers)));
  }
  return o;
}

}  // namespace

DoubletResult run_doublet(const DoubletSetup& s, const std::string& case_name, const std::string& label) {
  // The markers of both cells (lattice units) at the start and after every sample_every-th
  // and the last step, copied in memory by a stage of the case's own (observe phase):
  // written to run.h5 as field outputs instead, they would cost ~15 % of the run.
  struct Frame {
    long step;
    std::vector<geometry::Polygon> cells;
  };
  std::vector<Frame> frames;
  CaseRunOptions options;
  options.configure = [&frames, &s](sim::Simulation& sim) {
    const membrane::ImmersedCells* cells = sim.cells();
    auto copy = [cells, &frames](long step) { frames.push_back({step, {cells->polygon(0), cells->polygon(1)}}); };
    copy(0);
    sim.add_stage(sim::Phase::observe, "marker_samples", [copy, &s](long n) {
      if ((n + 1) % s.sample_every == 0 || n + 1 == s.steps) copy(n + 1);
    });
  };
  const CaseRun run = run_case_scene(case_scene(kScene, overrides(s)), case_name, label, options);
  DoubletResult r;
  r.scene_text = run.file.scene_text();
  r.steps_done = run.summary.steps;
  r.diverged = !run.ok();
  const scene::MembraneSetup& M = *run.setup.membrane;
  const aggregation::MorseParameters& morse = *M.aggregation;
  const geometry::Domain dom = fluid::domain_of(run.setup.grid, run.setup.boundaries);
  aggregation::CellContacts agg(dom, morse);
  const geometry::Polygon &p0 = M.cells[0].shape, &p1 = M.cells[1].shape;
  r.discrete_rigid_gap = discrete_rigid_gap(dom, morse, p0, p1, measure(p0).R);

  // The gap series |C1 − C2| − R1 − R2 (C: marker mean, R: mean radius) at every sample
  // after the start, the pair's centre unwrapped from sample to sample, marker 0's turn.
  Shape a = measure(frames.front().cells[0]), b = measure(frames.front().cells[1]);
  double comx = 0.5 * (a.cx + b.cx), comy = 0.5 * (a.cy + b.cy), dcx = 0.0, dcy = 0.0;
  auto angle0 = [](const geometry::Polygon& p, const Shape& sh) { return std::atan2(p.y[0] - sh.cy, p.x[0] - sh.cx); };
  double th0 = angle0(frames.front().cells[0], a), th1 = angle0(frames.front().cells[1], b), rot0 = 0.0, rot1 = 0.0;
  for (std::size_t f = 1; f < frames.size(); ++f) {
    const auto& cells = frames[f].cells;
    a = measure(cells[0]);
    b = measure(cells[1]);
    const double g = std::hypot(image(b.cx - a.cx, s.nx), image(b.cy - a.cy, s.ny)) - a.R - b.R;
    const double cx = 0.5 * (a.cx + b.cx), cy = 0.5 * (a.cy + b.cy);  // cells may be shifted by ±n
    dcx += image(cx - comx, 0.5 * s.nx);
    dcy += image(cy - comy, 0.5 * s.ny);
    comx = cx;
    comy = cy;
    const double t0 = angle0(cells[0], a), t1 = angle0(cells[1], b);
    rot0 += std::remainder(t0 - th0, 2.0 * std::numbers::pi);
    rot1 += std::remainder(t1 - th1, 2.0 * std::numbers::pi);
    th0 = t0;
    th1 = t1;
    r.step.push_back(double(frames[f].step));
    r.gap.push_back(g);
  }
  if (r.diverged) return r;
  r.final_gap = r.gap.empty() ? NAN : r.gap.back();
  const std::size_t n = r.gap.size();
  if (n >= 10) r.gap_change_last_10pc = std::abs(r.gap.back() - r.gap[n - 1 - n / 10]);
  r.com_drift = std::hypot(dcx, dcy);
  r.max_deformation = std::max(a.dev, b.dev);
  r.rotation_arc0 = rot0 * a.R;
  r.rotation_arc1 = rot1 * b.R;
  geometry::Polygon fa = frames.back().cells[0], fb = frames.back().cells[1];
  {
    // Force balance of the final state: the shift of cell 1 (frozen shape) along the
    // line of centres at which the net Morse force between the two membranes vanishes.
    double ex = image(b.cx - a.cx, s.nx), ey = image(b.cy - a.cy, s.ny);
    const double D = std::hypot(ex, ey);
    ex /= D;
    ey /= D;
    // Bring cell 1 next to cell 0 (undo a periodic shift) so plain differences apply.
    const double bx = a.cx + ex * D - b.cx, by = a.cy + ey * D - b.cy;
    geometry::Polygon near = fb;
    for (std::size_t i = 0; i < near.size(); ++i) {
      near.x[i] += bx;
      near.y[i] += by;
    }
    r.balance_shift = balance_root(agg, fa, near, ex, ey, -1.0, 1.0);
  }
  {
    // Relative contact areas of the final state (the aggregation forces on its markers).
    std::vector<double> x(fa.x), y(fa.y);
    x.insert(x.end(), fb.x.begin(), fb.x.end());
    y.insert(y.end(), fb.y.begin(), fb.y.end());
    const std::vector<std::size_t> off{0, fa.size(), fa.size() + fb.size()};
    std::vector<double> fx(x.size(), 0.0), fy(x.size(), 0.0);
    agg.add_forces(aggregation::MarkerView{x, y, off}, fx, fy);
    r.contact_area0 = aggregation::relative_contact_area(agg.force_magnitude(), off, 0);
    r.contact_area1 = aggregation::relative_contact_area(agg.force_magnitude(), off, 1);
  }
  r.wall_time_s = run.wall_time_s;
  return r;
}

}  // namespace erythro::vv
