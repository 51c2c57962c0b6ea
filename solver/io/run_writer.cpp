#include "io/run_writer.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <string>

#include "common/build_info.hpp"
#include "common/error.hpp"
#include "io/atomic_file.hpp"

namespace erythro::io {
namespace {
constexpr const char* kH5Name = "run.h5";
constexpr const char* kXdmfName = "run.xdmf";

// /metadata/cell_populations/<i>: what [[cell_populations]] entry i placed (scene/cell_seeding.hpp),
// so a run's cells can be traced to their seed without re-running the placement.
void write_cell_populations(hid_t meta, const scene::Scene& scene) {
  if (scene.cell_populations.empty()) return;
  h5::Handle group = h5::create_group(meta, "cell_populations");
  for (std::size_t i = 0; i < scene.cell_populations.size(); ++i) {
    const scene::CellPopulationSpec& pop = scene.cell_populations[i];
    const scene::PopulationPlacement& placed = scene.population_placements[i];
    h5::Handle g = h5::create_group(group.id(), std::to_string(i));
    if (pop.count) h5::write_attr(g.id(), "target_count", *pop.count);
    if (pop.area_fraction) h5::write_attr(g.id(), "target_area_fraction", *pop.area_fraction);
    h5::write_attrs(g.id(), {{"seed", pop.seed},
                             {"area_fraction", placed.area_fraction},
                             {"first_cell", static_cast<long>(placed.first_cell)},
                             {"cell_count", static_cast<long>(placed.count)}});
    std::vector<double> x, y, angle;
    for (std::size_t c = placed.first_cell; c < placed.first_cell + placed.count; ++c) {
      x.push_back(scene.cells[c].center_um[0]);
      y.push_back(scene.cells[c].center_um[1]);
      angle.push_back(scene.cells[c].angle_deg);
    }
    h5::write_attr(g.id(), "center_x_um", x);
    h5::write_attr(g.id(), "center_y_um", y);
    h5::write_attr(g.id(), "angle_deg", angle);
  }
}

// The aggregation strength in physical terms (docs/model.md eqs 4.7–4.8): γ, De* = γ / 2.6e-8
// J/m², the estimate γβ/2 of the largest Morse stress and, in a wall-driven simple shear, its
// ratio to the plasma's viscous stress μγ̇.
void write_aggregation_strength(hid_t meta, const scene::AggregationStrength& g) {
  h5::write_attrs(meta, {{"aggregation_surface_energy_J_m2", g.surface_energy_J_m2},
                         {"aggregation_de_star", g.de_star},
                         {"aggregation_peak_adhesion_stress_Pa", g.peak_stress_Pa}});
  if (g.shear_rate_per_s && g.adhesion_to_viscous_stress)
    h5::write_attrs(meta, {{"aggregation_shear_rate_1_s", *g.shear_rate_per_s},
                           {"aggregation_adhesion_to_viscous_stress", *g.adhesion_to_viscous_stress}});
}

std::string frame_group_name(long step) {
  char name[32];
  std::snprintf(name, sizeof name, "%010ld", step);
  return name;
}

// The `units` attribute of dataset `name` in `group`.
void write_units(hid_t group, const std::string& name, const std::string& units) {
  h5::Handle dataset = h5::open_dataset(group, name);
  h5::write_attr(dataset.id(), "units", units);
  dataset.close();
}
}  // namespace

template <class Write>
void RunWriter::guarded(Write&& write) {
  try {
    write();
  } catch (const std::exception& e) {
    discard();
    throw OutputError("cannot write '" + h5_path() + "': " + e.what() +
                      "; the unfinished file was removed and nothing was put in its place");
  }
}

RunWriter::RunWriter(std::string out_dir) : out_dir_(std::move(out_dir)) {
  guarded([&] { file_ = h5::create_file(temporary_path_for(h5_path())); });
}

RunWriter::~RunWriter() {
  try {
    abort("the run ended before its output was finished");
  } catch (...) {
    // A destructor must not throw; abort has removed the temporary file.
  }
}

std::string RunWriter::h5_path() const { return (std::filesystem::path(out_dir_) / kH5Name).string(); }
std::string RunWriter::xdmf_path() const { return (std::filesystem::path(out_dir_) / kXdmfName).string(); }

void RunWriter::on_start(const scene::Scene& scene, const scene::LatticeSetup& setup) {
  guarded([&] {
    setup_ = setup;
    const hid_t root = file_.id();
    h5::Handle meta = h5::create_group(root, "metadata");
    h5::write_attrs(meta.id(), {{"erythro_version", build_info::version()},
                                {"git_revision", build_info::git_revision()},
                                {"compiler", build_info::compiler()},
                                {"compile_flags", build_info::compile_flags()},
                                {"threads", static_cast<long>(omp_get_max_threads())},
                                {"scene_path", scene.source_path},
                                {"scene_text", scene.source_text},
                                {"scene_name", scene.name},
                                {"status", "running"},
                                {"spacing_um", setup.scales.length_m * 1e6},
                                {"time_step_s", setup.scales.time_s},
                                {"reference_density_kg_m3", setup.scales.density_kg_m3},
                                {"tau", setup.collision.tau},
                                {"collision", std::string(fluid::to_string(setup.collision.model))},
                                {"trt_magic", setup.collision.trt_magic},
                                {"lattice_viscosity", setup.viscosity},
                                {"expected_mach", setup.mach},
                                {"reynolds", setup.reynolds},
                                {"total_steps", setup.total_steps},
                                {"coupling", !setup.has_fluid ? "no fluid"
                                             : setup.membrane ? "immersed boundary"
                                                              : "fluid only"}});
    if (const auto& m = setup.time_mapping)  // docs/model.md eq 10.8: the density above is ρ_run
      h5::write_attrs(meta.id(), {{"time_mapping_reynolds", m->reynolds},
                                  {"time_mapping_physical_reynolds", m->physical_reynolds},
                                  {"time_mapping_shear_rate_per_s", m->shear_rate_per_s},
                                  {"time_mapping_radius_um", m->radius_m * 1e6},
                                  {"physical_density_kg_m3", m->physical_density_kg_m3}});
    if (const auto& T = setup.transport) {
      std::string names;
      for (const auto& sp : T->species) names += (names.empty() ? "" : ",") + sp.name;
      const std::string hemoglobin =
          T->hemoglobin_species >= 0 ? T->species[static_cast<std::size_t>(T->hemoglobin_species)].name : "";
      h5::write_attrs(meta.id(), {{"transport_coupling", T->coupling},
                                  {"transport_time_step_s", T->time_step_s},
                                  {"fluid_steps_per_transport_step", T->fluid_steps_per_step},
                                  {"species", names},
                                  {"hemoglobin_species", hemoglobin}});
      // docs/model.md §7b: x the axis z, y the radius from inner_radius_um
      const double h_um = setup.scales.length_m * 1e6;
      h5::write_attrs(meta.id(), {{"geometry", T->axisymmetric_inner_radius ? "axisymmetric" : "planar"},
                                  {"inner_radius_um", T->axisymmetric_inner_radius.value_or(0.0) * h_um}});
    }
    if (setup.membrane) {
      const auto& law = setup.membrane->model.tension.type;
      h5::write_attrs(meta.id(), {{"cell_count", static_cast<long>(setup.membrane->cells.size())},
                                  {"membrane_kernel", std::string(ib::to_string(setup.membrane->kernel))},
                                  {"membrane_law", std::string(membrane::to_string(law))},
                                  {"interior_method", std::string(interior::to_string(setup.membrane->indicator))},
                                  {"interior_lattice_viscosity", setup.membrane->interior_viscosity},
                                  {"index_update_interval", setup.membrane->index_update_interval},
                                  {"aggregation", setup.membrane->aggregation ? "morse" : "none"}});
      if (const auto& a = setup.membrane->aggregation)
        h5::write_attrs(meta.id(), {{"morse_De_lattice", a->De},
                                    {"morse_r0_lattice", a->r0},
                                    {"morse_beta_lattice", a->beta},
                                    {"morse_cutoff_lattice", a->cutoff}});
      if (const auto& g = setup.membrane->aggregation_strength) write_aggregation_strength(meta.id(), *g);
      if (const auto& r = setup.membrane->repulsion)
        h5::write_attrs(meta.id(), {{"repulsion_pressure_lattice", r->pressure},
                                    {"repulsion_range_lattice", r->range},
                                    {"repulsion_range_um", r->range * setup.scales.length_m * 1e6},
                                    {"repulsion_walls", std::string(r->walls ? "true" : "false")}});
    }
    write_cell_populations(meta.id(), scene);

    h5::Handle grid = h5::create_group(root, "grid");
    const double h_um = setup.scales.length_m * 1e6;
    h5::write_attrs(grid.id(), {{"nx", static_cast<long>(setup.grid.nx)},
                                {"ny", static_cast<long>(setup.grid.ny)},
                                {"spacing_um", h_um}});
    h5::write_attr(grid.id(), "origin_um", std::vector<double>{0.5 * h_um, 0.5 * h_um});

    diagnostics_group_ = h5::create_group(root, "diagnostics");
    fields_group_ = h5::create_group(root, "fields");
    if (setup.membrane) cells_group_ = h5::create_group(root, "cells");

    const auto& f = scene.output.fields;
    write_density_ = setup.has_fluid && std::find(f.begin(), f.end(), "density") != f.end();
    write_velocity_ = setup.has_fluid && std::find(f.begin(), f.end(), "velocity") != f.end();
    XdmfGrid xdmf_grid{setup.grid.nx, setup.grid.ny, h_um, 0.5 * h_um, 0.5 * h_um, {}, {}};
    if (write_density_) xdmf_grid.scalar_fields.push_back("density");
    if (write_velocity_) xdmf_grid.vector_fields.push_back("velocity");
    if (setup.transport)
      for (const auto& sp : setup.transport->species) xdmf_grid.scalar_fields.push_back(sp.name);
    h5::flush(root);
    xdmf_grid_ = std::move(xdmf_grid);
  });
}

void RunWriter::on_series_declared(std::span<const sim::SeriesInfo> series) {
  guarded([&] {
    for (const sim::SeriesInfo& info : series) {
      series_.push_back(std::make_unique<h5::AppendableSeries>(diagnostics_group_.id(), info.name));
      h5::write_attrs(series_.back()->id(), {{"units", info.unit}, {"description", info.description}});
    }
  });
}

void RunWriter::on_sample(long /*step*/, std::span<const double> values) {
  // Buffered: written in blocks (every kFlushSamples samples or kFlushSeconds of wall
  // time, and at every field output and at the end), so a run with many samples does not
  // pay one HDF5 extension per value, and a killed run loses at most one block.
  if (pending_.size() < series_.size()) pending_.resize(series_.size());
  for (std::size_t k = 0; k < values.size() && k < series_.size(); ++k) pending_[k].push_back(values[k]);
  ++pending_samples_;
  if (profiles_.empty()) flush_if_due();  // otherwise after the sample's profiles (on_profiles)
}

void RunWriter::on_profiles_declared(std::span<const sim::ProfileInfo> profiles) {
  guarded([&] {
    profiles_group_ = h5::create_group(file_.id(), "profiles");
    const auto ny = static_cast<std::size_t>(setup_.grid.ny);
    const double h_um = setup_.scales.length_m * 1e6;
    std::vector<double> y(ny);
    for (std::size_t j = 0; j < ny; ++j) y[j] = (static_cast<double>(j) + 0.5) * h_um;
    h5::write_dataset(profiles_group_.id(), "y_um", y);
    write_units(profiles_group_.id(), "y_um", "um");
    for (const sim::ProfileInfo& info : profiles) {
      profiles_.push_back(std::make_unique<h5::AppendableSeries>(profiles_group_.id(), info.name, ny));
      h5::write_attrs(profiles_.back()->id(), {{"units", info.unit}, {"description", info.description}});
    }
    pending_profiles_.assign(profiles_.size(), {});
  });
}

void RunWriter::on_profiles(long /*step*/, std::span<const double> values) {
  // Buffered with the diagnostics samples, and written with them: row k of a profile is
  // always the sample of /diagnostics/step[k], also in a file cut short by a kill.
  const std::size_t rows = static_cast<std::size_t>(setup_.grid.ny);
  for (std::size_t k = 0; k < pending_profiles_.size() && (k + 1) * rows <= values.size(); ++k)
    pending_profiles_[k].insert(pending_profiles_[k].end(), values.begin() + static_cast<std::ptrdiff_t>(k * rows),
                                values.begin() + static_cast<std::ptrdiff_t>((k + 1) * rows));
  flush_if_due();
}

void RunWriter::flush_if_due() {
  const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_flush_).count();
  if (pending_samples_ >= kFlushSamples || since >= kFlushSeconds) guarded([&] { flush_samples(); });
}

void RunWriter::flush_samples() {
  last_flush_ = std::chrono::steady_clock::now();
  if (pending_samples_ == 0) return;
  for (std::size_t k = 0; k < pending_.size(); ++k) {
    series_[k]->append(pending_[k]);
    pending_[k].clear();
  }
  for (std::size_t k = 0; k < pending_profiles_.size(); ++k) {
    profiles_[k]->append(pending_profiles_[k]);
    pending_profiles_[k].clear();
  }
  pending_samples_ = 0;
  h5::flush(file_.id());
}

XdmfFrame& RunWriter::xdmf_frame(long step) {
  if (has_frame_ && frame_.step != step) commit_xdmf_frame();
  if (!has_frame_) {
    frame_ = {step, static_cast<double>(step) * setup_.scales.time_s, "", "", 0};
    has_frame_ = true;
  }
  return frame_;
}

void RunWriter::commit_xdmf_frame() {
  if (has_frame_) xdmf_frames_.push_back(frame_);
  has_frame_ = false;
}

h5::Handle RunWriter::frame_group(long step) {
  const std::string name = frame_group_name(step);
  if (h5::exists(fields_group_.id(), name)) return h5::open_group(fields_group_.id(), name);
  h5::Handle frame = h5::create_group(fields_group_.id(), name);
  const double time_s = static_cast<double>(step) * setup_.scales.time_s;
  h5::write_attrs(frame.id(), {{"step", step}, {"time_s", time_s}});
  xdmf_frame(step).fields_group = "/fields/" + name;
  return frame;
}

void RunWriter::on_transport_fields(long step, const sim::TransportFields& f) {
  guarded([&] {
    flush_samples();
    h5::Handle frame = frame_group(step);
    const Grid& g = setup_.grid;
    const std::vector<hsize_t> shape{static_cast<hsize_t>(g.ny), static_cast<hsize_t>(g.nx)};
    for (std::size_t i = 0; i < f.names.size(); ++i) {
      const std::vector<double> concentration(f.concentration[i].begin(), f.concentration[i].end());
      h5::write_dataset(frame.id(), f.names[i], concentration, shape);
      write_units(frame.id(), f.names[i], "uM");
    }
    frame.close();
    h5::flush(file_.id());
  });
}

void RunWriter::on_fields(long step, const fluid::Moments& m) {
  guarded([&] {
    flush_samples();
    const auto& s = setup_.scales;
    const Grid& g = setup_.grid;
    h5::Handle frame = frame_group(step);
    const std::vector<hsize_t> shape{static_cast<hsize_t>(g.ny), static_cast<hsize_t>(g.nx)};
    if (write_density_) {
      std::vector<double> rho(m.rho.size());
      std::transform(m.rho.begin(), m.rho.end(), rho.begin(), [&](double r) { return r * s.density_kg_m3; });
      h5::write_dataset(frame.id(), "density", rho, shape);
      write_units(frame.id(), "density", "kg/m^3");
    }
    if (write_velocity_) {  // (ny, nx, 3): x, y and a zero z component (a vector in the x–y plane)
      const double to_um_s = s.velocity_m_s() * 1e6;
      std::vector<double> u(3 * m.ux.size(), 0.0);
      for (std::size_t n = 0; n < m.ux.size(); ++n) {
        u[3 * n] = m.ux[n] * to_um_s;
        u[3 * n + 1] = m.uy[n] * to_um_s;
      }
      h5::write_dataset(frame.id(), "velocity", u, {shape[0], shape[1], 3});
      write_units(frame.id(), "velocity", "um/s");
    }
    frame.close();
    h5::flush(file_.id());
  });
}

void RunWriter::on_cells(long step, const membrane::ImmersedCells& cells) {
  if (!cells_group_.valid()) return;
  guarded([&] {
    const auto& s = setup_.scales;
    const double to_um = s.length_m * 1e6;
    h5::Handle frame = h5::create_group(cells_group_.id(), frame_group_name(step));
    h5::write_attrs(frame.id(), {{"step", step},
                                 {"time_s", static_cast<double>(step) * s.time_s},
                                 {"cells", static_cast<long>(cells.cell_count())}});
    const std::size_t M = cells.marker_count();
    std::vector<double> xy(2 * M);
    std::vector<long> offsets, edges(2 * M), cell(M);
    for (int c = 0; c < cells.cell_count(); ++c) {
      const std::size_t o = cells.offset(c), n = cells.size(c);
      offsets.push_back(static_cast<long>(o));
      const auto x = cells.x(c), y = cells.y(c);
      for (std::size_t m = 0; m < n; ++m) {
        xy[2 * (o + m)] = x[m] * to_um;
        xy[2 * (o + m) + 1] = y[m] * to_um;
        edges[2 * (o + m)] = static_cast<long>(o + m);                 // edge m joins marker m to m + 1,
        edges[2 * (o + m) + 1] = static_cast<long>(o + (m + 1) % n);   // the last one back to marker 0
        cell[o + m] = c;
      }
    }
    offsets.push_back(static_cast<long>(M));
    const hsize_t markers = M;
    h5::write_dataset(frame.id(), "positions", xy, {markers, 2});
    write_units(frame.id(), "positions", "um");
    h5::write_dataset(frame.id(), "offsets", offsets, {static_cast<hsize_t>(offsets.size())});
    h5::write_dataset(frame.id(), "edges", edges, {markers, 2});
    h5::write_dataset(frame.id(), "cell", cell, {markers});
    frame.close();
    h5::flush(file_.id());
    XdmfFrame& f = xdmf_frame(step);
    f.cells_group = "/cells/" + frame_group_name(step);
    f.markers = static_cast<long>(M);
  });
}

void RunWriter::on_finish(const sim::RunSummary& summary) {
  guarded([&] {
    flush_samples();
    commit_xdmf_frame();
    h5::Handle meta = h5::open_group(file_.id(), "metadata");
    h5::write_attrs(meta.id(), {{"status", sim::to_string(summary.status)},
                                {"diagnosis", summary.diagnosis},
                                {"steps", summary.steps},
                                {"wall_time_s", summary.wall_time_s},
                                {"index_field_time_s", summary.index_field_time_s},
                                {"index_field_exposed_time_s", summary.index_field_exposed_time_s},
                                {"index_field_rebuilds", summary.index_field_rebuilds},
                                {"index_field_rebuilds_beside_forces", summary.index_field_rebuilds_beside_forces},
                                {"mlups", summary.mlups}});
    meta.close();
    // Wall time of every stage of the time loop (s) and how often it ran.
    h5::Handle timing = h5::create_group(file_.id(), "timing");
    for (const sim::StageTiming& t : summary.stages) {
      h5::write_attr(timing.id(), t.name + "_s", t.seconds);
      h5::write_attr(timing.id(), t.name + "_calls", t.calls);
    }
    timing.close();
    close_and_commit();
  });
  write_xdmf();
}

void RunWriter::abort(const std::string& reason) {
  if (finished_) return;
  guarded([&] {
    flush_samples();
    commit_xdmf_frame();
    if (h5::exists(file_.id(), "metadata")) {
      h5::Handle meta = h5::open_group(file_.id(), "metadata");
      h5::write_attr(meta.id(), "status", "aborted: " + reason);
      meta.close();
    }
    close_and_commit();
  });
  write_xdmf();
}

void RunWriter::close_and_commit() {
  close_file();
  // An earlier run's index (--force) would point at this run's file: it goes first, so
  // that a run killed between the two steps leaves run.h5 without an index, never a mix.
  std::error_code ec;
  std::filesystem::remove(xdmf_path(), ec);
  if (ec) throw OutputError("cannot remove the earlier '" + xdmf_path() + "': " + ec.message());
  commit_temporary(h5_path());
  finished_ = true;
}

void RunWriter::close_file() {
  for (auto& series : series_) series->close();
  series_.clear();
  for (auto& profile : profiles_) profile->close();
  profiles_.clear();
  profiles_group_.close();
  diagnostics_group_.close();
  fields_group_.close();
  cells_group_.close();
  file_.close();
}

void RunWriter::discard() noexcept {
  series_.clear();
  profiles_.clear();
  profiles_group_.reset();
  diagnostics_group_.reset();
  fields_group_.reset();
  cells_group_.reset();
  file_.reset();
  discard_temporary(h5_path());
  finished_ = true;
}

void RunWriter::write_xdmf() {
  if (!xdmf_grid_) return;  // the run ended before it started: no grid to index
  try {
    write_text_atomically(xdmf_path(), make_xdmf(kH5Name, *xdmf_grid_, xdmf_frames_));
  } catch (const OutputError& e) {
    throw OutputError(std::string(e.what()) + "; '" + h5_path() + "' is complete (open it without the XDMF index)");
  }
}

}  // namespace erythro::io
