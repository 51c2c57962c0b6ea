#include "deoxy_run.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/error.hpp"
#include "common/scene_case.hpp"
#include "geometry/grid_polygon.hpp"
#include "simulation/cell_transport.hpp"
#include "simulation/series_recorder.hpp"

namespace erythro::deoxy {

double diffusive_dt(double h_um, double dt_at_0p2_s) { return dt_at_0p2_s * (h_um / 0.2) * (h_um / 0.2); }

namespace {

const char* kPlanarScene = "validation/deoxygenation/deoxygenation.toml";
const char* kAxisymmetricScene = "validation/deoxygenation/deoxygenation_axisymmetric.toml";
const char* scene_of(const Setup& s) { return s.geometry == Geometry::planar ? kPlanarScene : kAxisymmetricScene; }

std::string quoted(const char* s) { return std::string("\"") + s + "\""; }

const char* representation_name(Representation r) { return r == Representation::ray_cast ? "ray_cast" : "area_fraction"; }
const char* heme_weights_name(Representation r) {
  return r == Representation::area_fraction_moment            ? "first_moment"
         : r == Representation::area_fraction_moment_sampling ? "first_moment_sampling"
                                                              : "area_fraction";
}
const char* coupling_name(Coupling c) {
  return c == Coupling::explicit_lagged ? "explicit" : c == Coupling::cell_implicit ? "cell_implicit"
                                                                                    : "cell_implicit_outflow";
}
const char* interface_name(InterfaceRule r) {
  return r == InterfaceRule::series ? "series" : r == InterfaceRule::node_tensor ? "node_tensor" : "face_tensor";
}

}  // namespace

std::vector<std::string> scene_overrides(const Setup& s) {
  using vv::set;
  const long n = std::lround(2.0 * s.box_half_um / s.h_um);
  // at least t_end (a Δt that does not divide t_end overshoots by < Δt; never stops short of it)
  const long steps = static_cast<long>(std::ceil(s.t_end_s / s.dt_s - 1e-9));
  // samples: every step up to 2 ms, then every 0.2 ms, and the last step
  const long stride = std::max(1L, std::lround(2e-4 / s.dt_s));
  long dense = 0;
  while (static_cast<double>(dense + 1) * s.dt_s <= 2e-3 + 1e-12) ++dense;
  const double C0_in = s.C0_in_uM < 0.0 ? s.hb.alpha * s.P0_torr : s.C0_in_uM;
  // Divergence guard: C stays in [min(C_b, C0_in), max(C_b, C0_in)] (maximum principle: the
  // release only restores P towards what the heme held at P0); [−C_max, 2 C_max], C_max =
  // max(C_b, C0_in), catches a growing oscillation long before it is a NaN.
  const double C_ceiling = 2.0 * std::max(s.C_b_uM, C0_in);
  const double L = static_cast<double>(n) * s.h_um;
  const bool axi = s.geometry == Geometry::axisymmetric;  // z ∈ [−L/2, L/2], r ∈ [0, L/2]
  std::vector<std::string> o = {
      set("domain.spacing_um", s.h_um),
      set("domain.size_um", L, axi ? 0.5 * L : L),
      set("transport.time_step_s", s.dt_s),
      set("run.steps", steps),
      set("output.diagnostics_interval_steps", stride),
      set("output.dense_diagnostics_steps", dense),
      set("monitor.interval_steps", stride),
      set("monitor.concentration_range_uM", -0.5 * C_ceiling, C_ceiling),
      set("transport.collision", quoted(s.collision.kind == transport::Collision::trt ? "trt" : "bgk")),
      set("transport.trt_magic", s.collision.magic),
      set("transport.cell_representation", quoted(representation_name(s.representation))),
      set("transport.interface", quoted(interface_name(s.interface))),
      set("species[0].diffusivity_um2_s", s.D_out),
      set("species[0].cell_diffusivity_um2_s", s.D_in),
      set("species[0].initial_uM", s.C_b_uM),
      set("species[0].cell_initial_uM", C0_in),
      set("hemoglobin.k_off_per_s", s.hb.k_off),
      set("hemoglobin.heme_uM", s.hb.C_heme),
      set("hemoglobin.solubility_uM_per_torr", s.hb.alpha),
      set("hemoglobin.p50_torr", s.hb.P50),
      set("hemoglobin.hill_n", s.hb.n),
      set("hemoglobin.rate_modifier", s.hb.M),
      set("hemoglobin.initial_saturation", transport::hill_saturation(s.P0_torr, s.hb.P50, s.hb.n)),
      set("hemoglobin.coupling", quoted(coupling_name(s.coupling))),
      set("hemoglobin.kinetics", quoted(s.kinetics == Kinetics::local ? "local" : "cell_mean")),
      set("hemoglobin.mean_pressure", quoted(s.source_corrected_P ? "source_corrected" : "concentration")),
      set("hemoglobin.heme_weights", quoted(heme_weights_name(s.representation))),
      set("cells[0].radius_um", s.a_um),
      set("cells[0].center_um", (0.5 * static_cast<double>(n) + s.offset_x_h) * s.h_um,
          axi ? 0.0 : (0.5 * static_cast<double>(n) + s.offset_y_h) * s.h_um),
      set("cells[0].markers", static_cast<long>(s.markers))};
  for (const char* side : {"left", "right", "bottom", "top"})
    if (!(axi && std::string(side) == "bottom"))  // the axis
      o.push_back(set(std::string("species[0].") + side + "_value", s.C_b_uM));
  return o;
}

Result run(const Setup& s, const std::string& case_name, const std::string& label, bool keep) {
  const scene::Scene scene = vv::case_scene(scene_of(s), scene_overrides(s));
  sim::SeriesRecorder recorder;
  vv::CaseRunOptions options;
  options.observers = {&recorder};
  options.keep = keep;
  const vv::CaseRun r = vv::run_case_scene(scene, case_name, label, options);
  if (!r.ok())
    throw std::runtime_error("deoxy::run diverged: " + r.summary.diagnosis + "; h = " + std::to_string(s.h_um) +
                             " um, dt = " + std::to_string(s.dt_s * 1e6) + " us, D_in = " + std::to_string(s.D_in) +
                             ", D_out = " + std::to_string(s.D_out) + " um^2/s, M = " + std::to_string(s.hb.M));
  Result res;
  res.S.t = recorder.series("time_s");
  res.S.y = recorder.series("cell_0_saturation");
  res.steps = r.summary.steps;
  res.nodes = r.setup.grid.nx;
  // The cell's nodes as the transport sees them (a static property of the placed polygon).
  const geometry::Polygon& cell = r.setup.membrane->cells.at(0).shape;
  const auto& T = *r.setup.transport;
  const bool axi = T.axisymmetric_inner_radius.has_value();
  std::vector<double> radius;  // r of each row, lattice units (model.md §7b: r_y = r_in + y + ½)
  if (axi)
    for (int y = 0; y < r.setup.grid.ny; ++y) radius.push_back(*T.axisymmetric_inner_radius + y + 0.5);
  const sim::CellNodes nodes = sim::cell_nodes(cell, geometry::Domain{r.setup.grid, false, false},
                                               T.cell_representation, T.heme_weights, radius);
  res.interior_nodes = static_cast<long>(nodes.heme.size());
  res.interior_area_um2 = axi ? 2.0 * M_PI * nodes.heme_volume * s.h_um * s.h_um * s.h_um : nodes.heme_sum * s.h_um * s.h_um;
  res.polygon_area_um2 = std::abs(geometry::signed_area(cell)) * s.h_um * s.h_um;
  const std::string per = axi ? "_uM_um3" : "_uM_um2";
  res.released_uM_um2 = recorder.series("cell_0_released" + per).back();
  res.medium_change_uM_um2 = recorder.series("O2_amount_change" + per).back();
  res.boundary_in_uM_um2 = recorder.series("O2_boundary_inflow" + per).back();
  res.balance_residual = (res.medium_change_uM_um2 - res.boundary_in_uM_um2 - res.released_uM_um2) / res.released_uM_um2;
  res.max_step_residual = recorder.series("O2_max_mass_balance_residual").back();
  res.wall_s = r.wall_time_s;
  res.scene_text = r.file.scene_text();
  return res;
}

std::vector<io::FieldPicture> transient_pictures(Setup s, double t_s, const std::string& case_name,
                                                 const std::string& label) {
  s.t_end_s = t_s;
  vv::CaseRunOptions options;
  options.pictures = true;
  vv::CaseRun r = vv::run_case_scene(vv::case_scene(scene_of(s), scene_overrides(s)), case_name, label, options);
  if (!r.ok()) throw std::runtime_error("deoxy::transient_pictures: the run diverged: " + r.summary.diagnosis);
  return std::move(r.pictures);
}

vv::Curve read_reference(const std::string& path, int column) {
  std::ifstream in(path);
  if (!in) throw InputError("deoxy: cannot read the reference curve " + path + " (reference_rbc.py --study)");
  vv::Curve c;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::stringstream ss(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
    if (static_cast<int>(v.size()) <= column) throw InputError("deoxy: short row in " + path);
    c.t.push_back(v[0]);
    c.y.push_back(v[static_cast<std::size_t>(column)]);
  }
  if (c.t.size() < 10) throw InputError("deoxy: too few rows in " + path);
  return c;
}

}  // namespace erythro::deoxy
