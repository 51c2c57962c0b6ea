#include "rbc_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/scene_case.hpp"
#include "geometry/polygon.hpp"

namespace erythro::vv {

namespace {
constexpr const char* kScene = "validation/rbc/rbc.toml";
constexpr double kPerimeterOverA = 19.271 / 3.91;  // docs/parameters.md (2D biconcave section)

// The overrides that set rbc.toml up for `c` (physical units, as a user would write them):
// h, the domain H × L_x, γ̇ from the lattice Reynolds number (Re = γ̇a²/ν at the plasma's
// ν; a τ other than 1 keeps Re), the wall speeds ∓γ̇H/2, the moduli that keep the thesis
// cell's Ca, E_B*, k_A a/E_S at that γ̇, the interior viscosity, the markers.
std::vector<std::string> physical_overrides(const RbcConfig& c, const scene::Scene& base, double& shear_rate,
                                            long& markers) {
  const double h_um = c.h_m * 1e6, a_um = c.a_m * 1e6, a = c.a_m / c.h_m;
  const int nx = static_cast<int>(std::lround(c.length * a)), ny = static_cast<int>(std::lround(c.height * a));
  const double mu = base.fluid.viscosity_cP * 1e-3, nu = mu / base.fluid.density_kg_m3;
  shear_rate = c.reynolds * nu / (c.a_m * c.a_m);                      // 1/s
  const double capillary = c.mu_Pa_s * c.shear_rate * c.a_m / c.Es_N_m;  // of the thesis cell
  const double bending_reduced = c.Eb_J / (c.a_m * c.a_m * c.Es_N_m);
  const double Es = mu * shear_rate * c.a_m / capillary;               // N/m
  const double U = 0.5 * shear_rate * ny * h_um;                       // µm/s
  markers = std::lround(kPerimeterOverA * a / c.marker_spacing);
  std::vector<std::string> o = {
      set("domain.spacing_um", h_um),
      set("domain.size_um", nx * h_um, ny * h_um),
      set("time.tau", c.tau),
      set("boundaries.bottom.velocity_um_s", -U, 0.0),
      set("boundaries.top.velocity_um_s", U, 0.0),
      set("monitor.max_mach", c.max_mach),
      set("monitor.max_edge_strain", c.max_edge_strain),
      set("membrane.kernel", "\"" + std::string(ib::to_string(c.kernel)) + "\""),
      set("membrane.shear_modulus_dyn_cm", Es * 1e3),
      set("membrane.bending_modulus_dyn_cm", bending_reduced * c.a_m * c.a_m * Es * 1e7),  // J → dyn·cm
      set("membrane.area_modulus_Pa", c.area_modulus * Es / c.a_m),
      set("cells[0].radius_um", a_um),
      // Mid-channel, 0.123 h off the lattice symmetry in x.
      set("cells[0].center_um", (0.5 * nx + 0.123) * h_um, 0.5 * ny * h_um),
      set("cells[0].markers", markers)};
  if (c.indicator != interior::Method::indexless) {
    o.push_back(set("membrane.interior_viscosity_cP", c.viscosity_ratio * base.fluid.viscosity_cP));
    o.push_back(set("membrane.interior_method", "\"" + std::string(interior::to_string(c.indicator)) + "\""));
    o.push_back(set("membrane.index_update_interval", static_cast<long>(c.index_update_interval)));
  }
  if (!c.require_stability_estimate) o.push_back(set("limits.membrane_stability", "\"warn\""));
  return o;
}

// The continued angle of the long axis and the membrane's turning from the probe's series
// (every sample), and the statistics the cases judge.
void read_histories(const io::RunFile& file, double gamma, RbcResult& r) {
  const auto& step = file.series("step");
  const auto& D = file.series("cell_0_taylor_deformation");
  const auto& theta = file.series("cell_0_inclination_deg");
  const auto& area = file.series("cell_0_area_change");
  const auto& edge = file.series("cell_0_max_edge_strain");
  const auto& phase = file.series("cell_0_marker_phase_deg");
  const auto& marker0 = file.series("cell_0_marker0_angle_deg");
  for (std::size_t k = 0; k < step.size(); ++k) {
    r.strain_h.push_back(step[k] * gamma);
    r.D_h.push_back(D[k]);
    r.theta_h.push_back(theta[k]);
    r.area_h.push_back(area[k]);
    r.estrain_h.push_back(edge[k]);
    r.psi_h.push_back(marker0[k] - theta[k]);  // ψ: marker 0 from the long axis
    r.phase_h.push_back(phase[k]);
  }
  r.marker0_rotation_deg = marker0.back() - marker0.front();
}

// Outlines (µm, about the area centroid, closed) at the field outputs nearest the wanted strains.
void read_snapshots(const io::RunFile& file, double gamma, const std::vector<double>& strains, RbcResult& r) {
  const auto& frames = file.cells();
  if (frames.empty()) return;
  for (double wanted : strains) {
    if (wanted > r.strain + 0.5) continue;
    const auto nearest = std::min_element(frames.begin(), frames.end(), [&](const auto& p, const auto& q) {
      return std::abs(static_cast<double>(p.step) * gamma - wanted) < std::abs(static_cast<double>(q.step) * gamma - wanted);
    });
    geometry::Polygon p;  // cell 0
    p.x.assign(nearest->x_um.begin() + static_cast<long>(nearest->offsets[0]),
               nearest->x_um.begin() + static_cast<long>(nearest->offsets[1]));
    p.y.assign(nearest->y_um.begin() + static_cast<long>(nearest->offsets[0]),
               nearest->y_um.begin() + static_cast<long>(nearest->offsets[1]));
    double cx = 0, cy = 0;
    geometry::centroid(p, cx, cy);
    ShapeSnapshot s;
    s.strain = static_cast<double>(nearest->step) * gamma;
    for (std::size_t m = 0; m <= p.size(); ++m) {  // closed: marker 0 repeated
      s.x_um.push_back(p.x[m % p.size()] - cx);
      s.y_um.push_back(p.y[m % p.size()] - cy);
    }
    r.snapshots.push_back(std::move(s));
  }
}
}  // namespace

std::string run_folder(const RbcConfig& c) {
  char b[160];
  std::snprintf(b, sizeof b, "%s_x%g_h%g_tau%g_Es%g_k%d_strain%g", std::string(interior::to_string(c.indicator)).c_str(),
                c.indicator == interior::Method::indexless ? 1.0 : c.viscosity_ratio, c.h_m * 1e6, c.tau, c.Es_N_m,
                c.index_update_interval, c.strain);
  return b;
}

std::string classify(const RbcResult& r) {
  if (r.diverged) return "undetermined";
  if (std::abs(r.body_rotation_deg) >= 90.0) return "tumbling";
  if (std::abs(r.marker_rotation_deg - r.body_rotation_deg) >= 90.0) return "tank-treading";
  return "undetermined";
}

RbcResult run_rbc(const RbcConfig& c, const std::string& case_name, const std::string& label) {
  RbcResult r;
  r.capillary = c.mu_Pa_s * c.shear_rate * c.a_m / c.Es_N_m;  // Ca = μγ̇a/E_S
  r.bending_reduced = c.Eb_J / (c.a_m * c.a_m * c.Es_N_m);     // E_B* = E_B/(a²E_S)
  r.reynolds_physical = 1000.0 * c.shear_rate * c.a_m * c.a_m / c.mu_Pa_s;
  double shear_rate = 0;
  long markers = 0;
  std::vector<std::string> set_up = physical_overrides(c, case_scene(kScene), shear_rate, markers);
  // Lattice shear rate, then the run length, sampling (0.05 strain units) and field outputs in steps.
  const scene::LatticeSetup first = scene::derive_lattice(case_scene(kScene, set_up));
  const double gamma = first.scales.time_s * shear_rate;
  const long steps = std::lround(c.strain / gamma);
  const long sample_every = std::max(1L, std::lround(0.05 / gamma));
  const bool inner_snapshots = std::any_of(c.snapshot_strains.begin(), c.snapshot_strains.end(),
                                           [&](double s) { return s > 0.0 && s < c.strain; });
  set_up.push_back(set("run.steps", steps));
  set_up.push_back(set("output.diagnostics_interval_steps", sample_every));
  set_up.push_back(set("monitor.interval_steps", sample_every));
  set_up.push_back(set("output.fields_interval_steps", inner_snapshots ? 10 * sample_every : 0L));
  CaseRunOptions options;
  options.pictures = c.pictures;
  const CaseRun run = run_case_scene(case_scene(kScene, set_up), case_name, label, options);

  const scene::MembraneSetup& M = *run.setup.membrane;
  r.scene_text = run.file.scene_text();
  r.pictures = run.pictures;
  r.a_lat = c.a_m / c.h_m;
  r.gamma_lat = gamma;
  r.Es_lat = M.model.tension.modulus;
  r.Eb_lat = M.model.bending;
  r.kA_lat = M.model.area_modulus;
  r.nx = run.setup.grid.nx;
  r.ny = run.setup.grid.ny;
  r.markers = static_cast<int>(markers);
  r.tau_ex = run.setup.collision.tau;
  r.tau_in = M.indicator == interior::Method::indexless ? r.tau_ex : M.interior_tau;
  r.stability_factor = M.stability.max_dt_factor;
  r.steps = run.summary.steps;
  r.wall_time_s = run.wall_time_s;
  r.index_time_s = run.summary.index_field_time_s;
  read_histories(run.file, gamma, r);
  r.max_area_change = run.file.series("cells_max_area_change").back();
  r.max_edge_strain = run.file.series("cells_max_edge_strain").back();
  if (M.indicator != interior::Method::indexless) {
    const auto& start = run.file.cells().front();  // the rest shape
    const double A0 = geometry::signed_area(std::span<const double>(start.x_um.data(), start.offsets[1]),
                                            std::span<const double>(start.y_um.data(), start.offsets[1]));
    r.index_updates = std::lround(run.file.series("interior_index_updates").back());
    r.fallback_cells = static_cast<int>(run.file.series("interior_max_fallback_cells").back());
    r.max_fill_mismatch = run.file.series("interior_max_fill_mismatch_um2").back() / A0;
    r.interior_fraction = run.file.series("interior_fill_fraction").back();
  }
  r.strain = r.strain_h.empty() ? 0.0 : r.strain_h.back();
  read_snapshots(run.file, gamma, c.snapshot_strains, r);
  if (!run.ok() || r.strain_h.size() < 3) {
    r.diverged = true;
    r.diagnosis = run.ok() ? "fewer than 3 samples" : run.summary.diagnosis;
    return r;
  }
  {  // rates over the second half of the run
    const std::size_t i0 = r.strain_h.size() / 2, i1 = r.strain_h.size() - 1;
    const double ds = r.strain_h[i1] - r.strain_h[i0];
    if (ds > 0) {
      r.marker_rate_deg = (r.phase_h[i1] - r.phase_h[i0]) / ds;
      r.body_rate_deg = (r.theta_h[i1] - r.theta_h[i0]) / ds;
    }
  }
  r.body_rotation_deg = r.theta_h.back() - r.theta_h.front();
  r.marker_rotation_deg = r.phase_h.back();
  r.theta_min = std::numeric_limits<double>::infinity();
  r.theta_max = -r.theta_min;
  double sD = 0, sT = 0;
  int k = 0;
  for (std::size_t i = 0; i < r.strain_h.size(); ++i) {
    if (r.strain_h[i] >= 2.0) {
      r.theta_min = std::min(r.theta_min, r.theta_h[i]);
      r.theta_max = std::max(r.theta_max, r.theta_h[i]);
    }
    if (r.strain_h[i] >= r.strain - 2.0) { sD += r.D_h[i]; sT += r.theta_h[i]; ++k; }
  }
  if (r.theta_min > r.theta_max) r.theta_min = r.theta_max = r.theta_h.back();  // run shorter than strain 2
  r.D_mean = sD / k;
  r.theta_mean = sT / k;
  r.centre_drift = std::abs(run.file.series("cell_0_centroid_y_um").back() - 0.5 * r.ny * c.h_m * 1e6) / (c.a_m * 1e6);
  return r;
}

}  // namespace erythro::vv
