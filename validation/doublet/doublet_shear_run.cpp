#include "doublet_shear_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

#include "aggregation/morse_units.hpp"
#include "common/concurrent_runs.hpp"
#include "common/scene_case.hpp"
#include "doublet_scene.hpp"
#include "membrane/stability.hpp"
#include "simulation/cell_physics.hpp"

namespace erythro::vv {

namespace {

// Outline pictures for the record (not a diagnostic): the cells' markers (µm, cell 1 at its
// nearest periodic image in x to cell 0, NaN between cells) at the first sample of every
// 2 strain units. A probe without series, so it sees exactly the samples, healthy states only.
class OutlineSnapshots : public sim::Probe {
 public:
  OutlineSnapshots(const sim::CellPhysics& cells, double gamma, DoubletShearResult& out)
      : cells_(cells), gamma_(gamma), out_(out) {}
  void declare(std::vector<sim::SeriesInfo>&) const override {}
  void sample(const sim::ProbeContext& context, std::span<double>) override {
    const double strain = static_cast<double>(context.step) * gamma_;
    if (strain < next_ - 0.5 * gamma_) return;
    const membrane::ImmersedCells& cells = cells_.cells();
    const double um = context.setup.scales.length_m * 1e6;
    const int nx = context.setup.grid.nx;
    std::vector<double> xs, ys;
    double cx0 = 0;
    for (int k = 0; k < cells.cell_count(); ++k) {
      const geometry::Polygon p = cells.polygon(k);
      double cx = 0, cy = 0;
      geometry::centroid(p, cx, cy);
      if (k == 0) cx0 = cx;
      const double shift = k == 0 ? 0.0 : nx * std::round((cx - cx0) / nx);
      if (k > 0) {
        xs.push_back(std::nan(""));
        ys.push_back(std::nan(""));
      }
      for (std::size_t m = 0; m <= p.size(); ++m) {
        xs.push_back((p.x[m % p.size()] - shift) * um);
        ys.push_back(p.y[m % p.size()] * um);
      }
    }
    out_.snap_strain.push_back(strain);
    out_.snap_x.push_back(std::move(xs));
    out_.snap_y.push_back(std::move(ys));
    next_ += 2.0;
  }

 private:
  const sim::CellPhysics& cells_;
  double gamma_, next_ = 0.0;
  DoubletShearResult& out_;
};

// The mapping of the physical inputs, for the record (lattice values of the set-up).
void fill_mapping(const DoubletShearConfig& c, const scene::LatticeSetup& setup, double gamma, DoubletShearResult& r) {
  r.capillary0 = c.mu_Pa_s * c.shear_rate * c.a_m / c.Es0_N_m;  // Ca = μγ̇a/E_S
  r.capillary1 = c.mu_Pa_s * c.shear_rate * c.a_m / c.Es1_N_m;
  r.bending_reduced = c.Eb_J / (c.a_m * c.a_m * c.Es0_N_m);
  r.reynolds_physical = 1000.0 * c.shear_rate * c.a_m * c.a_m / c.mu_Pa_s;  // water-like plasma
  r.a_lat = c.a_m / c.h_m;
  r.gamma_lat = gamma;
  r.nx = setup.grid.nx;
  r.ny = setup.grid.ny;
  r.markers = c.markers;
  const scene::MembraneSetup& M = *setup.membrane;
  r.tau_in = M.interior_tau;
  const membrane::MembraneModel& m0 = M.cells.front().model;
  const membrane::MembraneModel& m1 = M.cells.back().model;
  r.Es0_lat = m0.tension.modulus;
  r.Es1_lat = c.cells == 2 ? m1.tension.modulus : m0.tension.modulus;
  r.Eb_lat = m0.bending;
  r.kA_lat = m0.area_modulus;
  // Morse in lattice units (with De* = 0 and for the single cell too: the record shows the range).
  aggregation::MorseParameters morse{0.0, c.r0_m / c.h_m, c.beta_per_m * c.h_m, 0.0};
  morse.cutoff = morse.r0 + c.cutoff_k / morse.beta;
  r.De_lat = M.aggregation ? M.aggregation->De : 0.0;
  r.r0_lat = morse.r0;
  r.beta_lat = morse.beta;
  r.cutoff_lat = morse.cutoff;
  r.flat_gap_lat = aggregation::flat_contact(morse).gap;
  if (M.aggregation_strength) {  // as the scene derives it (run.h5 /metadata, `erythro check`)
    const scene::AggregationStrength& g = *M.aggregation_strength;
    r.surface_energy_J_m2 = g.surface_energy_J_m2;
    r.de_star = g.de_star;
    r.peak_adhesion_stress_Pa = g.peak_stress_Pa;
    r.adhesion_to_viscous_stress = g.adhesion_to_viscous_stress.value_or(-1.0);
  }
  // Explicit-update margin of the stiffer membrane at 20 % stretch, the slower viscosity.
  membrane::StabilityInput si;
  si.kernel = c.kernel;
  si.model = r.Es1_lat > r.Es0_lat ? m1 : m0;
  si.viscosity = std::min(setup.viscosity, M.interior_viscosity);
  si.max_stretch = 1.2;
  r.stability_factor = membrane::estimate_stability(si).max_dt_factor;
}

// The histories and outcome from the run's series (one entry per sample).
void fill_histories(const DoubletShearConfig& c, const io::RunFile& f, double gamma, DoubletShearResult& r) {
  const bool pair = c.cells == 2;
  const auto& step = f.series("step");
  const auto& theta = f.series(theta_series(c));
  const std::size_t n = step.size();
  const auto series_or_zero = [&](const char* name) { return pair ? f.series(name) : std::vector<double>(n, 0.0); };
  const std::vector<double> c0 = series_or_zero("cell_0_contact_area"), c1 = series_or_zero("cell_1_contact_area");
  const std::vector<double> sep = series_or_zero("pair_separation_um"), gap = series_or_zero("pair_gap_um");
  const std::vector<double> sig = series_or_zero("pair_contact_sigmoid_um"), bow = series_or_zero("pair_contact_bow_um");
  const std::vector<double> diss = series_or_zero("pair_dissociated");
  const auto& D0 = f.series("cell_0_taylor_deformation");
  const std::vector<double> D1 = pair ? f.series("cell_1_taylor_deformation") : std::vector<double>(n, 0.0);
  double aspect_sum = 0;
  int aspect_n = 0;
  r.min_contact_after1 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const double strain = step[i] * gamma;
    double area_change = 0;
    for (int k = 0; k < c.cells; ++k) {
      const std::string p = "cell_" + std::to_string(k) + "_";
      area_change = std::max(area_change, std::abs(f.series(p + "area_change")[i]));
      const double edge = f.series(p + "max_edge_strain")[i];
      r.max_edge_strain = std::max(r.max_edge_strain, edge);
      r.max_edge_strain_cell[k] = std::max(r.max_edge_strain_cell[k], edge);
    }
    r.max_area_change = std::max(r.max_area_change, area_change);
    // Single cell: the equivalent ellipse's a/b = (1 + D)/(1 − D) (geometry::taylor_deformation).
    const double aspect = pair ? f.series("pair_aspect_ratio")[i] : (1.0 + D0[i]) / (1.0 - D0[i]);
    if (pair && !r.dissociated && diss[i] > 0.5) {  // no marker pair within reach: no Morse force left
      r.dissociated = true;
      r.dissociation_strain = strain;
    }
    if (pair && strain >= 1.0 && !r.dissociated) r.min_contact_after1 = std::min(r.min_contact_after1, std::min(c0[i], c1[i]));
    // First crossings of 0, −90°, −180°, interpolated linearly between samples.
    auto crossing = [&](double level, double& t) {
      if (t >= 0 || theta[i] > level) return;
      if (r.strain_h.empty()) {
        t = strain;
        return;
      }
      const double ta = r.strain_h.back(), qa = r.theta_h.back();
      t = qa > theta[i] ? ta + (strain - ta) * (qa - level) / (qa - theta[i]) : strain;
    };
    crossing(0.0, r.t_theta0);
    crossing(-90.0, r.t_theta_m90);
    crossing(-180.0, r.t_theta_m180);
    if (r.t_theta0 >= 0 && r.t_theta_m90 < 0) {
      aspect_sum += aspect;
      ++aspect_n;
    }
    r.strain_h.push_back(strain);
    r.theta_h.push_back(theta[i]);
    r.contact0_h.push_back(c0[i]);
    r.contact1_h.push_back(c1[i]);
    r.separation_h.push_back(sep[i]);
    r.gap_h.push_back(gap[i]);
    r.D0_h.push_back(D0[i]);
    r.D1_h.push_back(D1[i]);
    r.sigmoid_h.push_back(sig[i]);
    r.bow_h.push_back(bow[i]);
    r.aspect_h.push_back(aspect);
    r.area_h.push_back(area_change);
  }
  if (aspect_n > 0) r.aspect_quadrant = aspect_sum / aspect_n;
  if (!r.strain_h.empty()) r.strain = r.strain_h.back();
  if (!std::isfinite(r.min_contact_after1)) r.min_contact_after1 = 0;
}

}  // namespace

DoubletShearResult run_doublet_shear(const DoubletShearConfig& c, const std::string& case_name,
                                     const std::string& label) {
  const DoubletScene d = doublet_scene(c);
  DoubletShearResult r;
  CaseRunOptions options;
  options.configure = [&](sim::Simulation& sim) {
    sim.add_probe(std::make_unique<OutlineSnapshots>(*sim.cell_physics(), d.gamma, r));
  };
  options.pictures = c.pictures;
  const CaseRun run = run_case_scene(d.scene, case_name, label, options);
  r.scene_text = run.file.scene_text();
  r.pictures = run.pictures;
  r.wall_time_s = run.wall_time_s;
  r.steps = run.summary.steps;
  r.diverged = !run.ok();
  if (r.diverged) r.diagnosis = run.summary.diagnosis;
  fill_mapping(c, run.setup, d.gamma, r);
  fill_histories(c, run.file, d.gamma, r);
  return r;
}

std::vector<DoubletShearResult> run_doublet_shears(const std::vector<DoubletRun>& runs, const std::string& case_name) {
  std::vector<DoubletShearResult> results(runs.size());
  std::vector<std::size_t> order(runs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto cost = [&](std::size_t i) { return runs[i].config.strain / std::pow(runs[i].config.h_m * 1e6, 4); };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost(a) > cost(b); });
  std::vector<std::function<void()>> jobs;
  for (std::size_t i : order)
    jobs.push_back([&, i] { results[i] = run_doublet_shear(runs[i].config, case_name, runs[i].label); });
  run_concurrently(jobs);
  return results;
}

}  // namespace erythro::vv
