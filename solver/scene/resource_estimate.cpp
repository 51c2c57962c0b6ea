// Memory and output of a run from its set-up's sizes (resource_estimate.hpp). Every count is
// a double (8 bytes) per node, per marker or per value, as the solver allocates it.
#include "scene/resource_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace erythro::scene {
namespace {

constexpr double kDouble = 8.0;

// How many times an output with period `interval` is written over `steps` steps: at step 0,
// at every multiple of the period, and at the last step (observation.cpp); 0: first and last.
double writes(long steps, long interval) {
  const double T = static_cast<double>(steps);
  if (interval <= 0) return 2.0;
  const double multiples = std::floor(T / static_cast<double>(interval));
  const bool last_is_multiple = steps % interval == 0;
  return 1.0 + multiples + (last_is_multiple ? 0.0 : 1.0);
}

double sum(const std::vector<ResourcePart>& parts) {
  return std::accumulate(parts.begin(), parts.end(), 0.0,
                         [](double total, const ResourcePart& p) { return total + p.bytes; });
}

}  // namespace

double ResourceEstimate::memory_bytes() const { return sum(memory); }
double ResourceEstimate::output_bytes() const { return sum(output); }

ResourceEstimate estimate_resources(const Scene& s, const LatticeSetup& L) {
  ResourceEstimate e;
  const double nodes = static_cast<double>(L.grid.nx) * static_cast<double>(L.grid.ny);
  const auto per_node = [&](const std::string& what, double doubles) {
    e.memory.push_back({what, doubles * nodes * kDouble});
  };

  double markers = 0.0;
  if (L.membrane)
    for (const CellSetup& c : L.membrane->cells) markers += static_cast<double>(c.shape.size());

  if (L.has_fluid) {
    // fluid/fluid_lattice.hpp: nine population arrays (AA pattern: one copy), and the
    // moments ρ, ux, uy gathered at every check, with the previous velocity kept by the
    // steady-state test.
    per_node("fluid populations (9 per node)", 9.0);
    per_node(s.run.steady_state ? "moments ρ, u and the steady-state test's previous u (5 per node)"
                                : "moments ρ, u (3 per node)",
             s.run.steady_state ? 5.0 : 3.0);
    const bool cells_move = L.membrane && !L.membrane->cells.empty();
    if (cells_move) per_node("immersed-boundary force field (2 per node)", 2.0);
    const bool index_field = L.membrane && L.membrane->indicator != interior::Method::indexless;
    if (index_field || !L.viscosity_layers.empty()) per_node("relaxation-time field τ (1 per node)", 1.0);
    // interior/index_field.hpp: the index (double), a mark byte and two ints per node.
    if (index_field) e.memory.push_back({"interior index field (17 B per node)", 17.0 * nodes});
  }
  if (L.transport) {
    // transport/transport_lattice.hpp per species: the populations twice (current and next),
    // C, D, source, decay, the advecting velocity (2) and, with the tensor interfaces, Dxx,
    // Dyy, Dxy; simulation/transport_physics.hpp adds the readout and the layer fields.
    const double q = L.transport->stencil == transport::Stencil::d2q9 ? 9.0 : 5.0;
    const bool tensor = L.transport->interface != "series";
    const double per_species = 2.0 * q + 6.0 + (tensor ? 3.0 : 0.0) + 3.0;
    const double count = static_cast<double>(L.transport->species.size());
    char what[96];
    std::snprintf(what, sizeof what, "transport, %g species (%g per node each)", count, per_species);
    per_node(what, per_species * count);
  }
  // Markers: positions, rest shape, velocities, forces, and the scratch of the membrane
  // update and the kernel spreading: about 20 doubles each.
  if (markers > 0.0) e.memory.push_back({"cell markers (about 20 values each)", 20.0 * markers * kDouble});

  // run.h5 (docs/cli.md): per field snapshot, density (1 per node), velocity (3: x, y and a
  // zero z) and one value per node per species; cells: positions (2), edges (2) and cell (1)
  // per marker; diagnostics: one value per series per sample; a channel's profiles: ny values
  // per profile per sample.
  const long steps = L.total_steps;
  e.field_snapshots = writes(steps, s.output.fields_interval_steps);
  double per_snapshot = 0.0;
  if (L.has_fluid)
    for (const std::string& f : s.output.fields) per_snapshot += (f == "velocity" ? 3.0 : 1.0);
  if (L.transport) per_snapshot += static_cast<double>(L.transport->species.size());
  e.output.push_back({"fields", e.field_snapshots * per_snapshot * nodes * kDouble});
  // Markers are written with the fluid's fields only (a still medium's cells do not move).
  if (markers > 0.0 && L.has_fluid) e.output.push_back({"cells", e.field_snapshots * 5.0 * markers * kDouble});

  const double cells = L.membrane ? static_cast<double>(L.membrane->cells.size()) : 0.0;
  const double species = L.transport ? static_cast<double>(L.transport->species.size()) : 0.0;
  // step and time, 6 fluid series, 12 per moving cell + 3 over all cells, 4 of the interior,
  // 3 per species, a saturation per cell (simulation/probes/).
  const double series = 2.0 + (L.has_fluid ? 6.0 : 0.0) + (L.has_fluid && cells > 0.0 ? 12.0 * cells + 3.0 : 0.0) +
                        (L.membrane && L.membrane->indicator != interior::Method::indexless ? 4.0 : 0.0) +
                        3.0 * species + (L.transport && L.transport->hemoglobin ? cells : 0.0);
  e.diagnostics_samples = writes(steps, s.output.diagnostics_interval_steps) +
                          static_cast<double>(std::min(s.output.dense_diagnostics_steps, steps));
  e.output.push_back({"diagnostics", e.diagnostics_samples * series * kDouble});
  // A channel (the condition of sim::ChannelProbe::applies) writes 3 profiles of ny values
  // per sample (/profiles, simulation/probes/channel_profile_probe.hpp).
  const fluid::BoundaryConfig& b = L.boundaries;
  if (L.has_fluid && b.left.type == fluid::SideType::periodic && b.bottom.type == fluid::SideType::wall &&
      b.top.type == fluid::SideType::wall && L.body_force[0] != 0.0 && L.body_force[1] == 0.0 &&
      L.force_frequency == 0.0)
    e.output.push_back({"profiles", e.diagnostics_samples * 3.0 * L.grid.ny * kDouble});
  return e;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 6) {
    bytes /= 1000.0;
    ++u;
  }
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3g %s", bytes, units[u]);
  return buf;
}

std::string format_resource_report(const ResourceEstimate& e) {
  std::string out = "  memory (estimate)         " + format_bytes(e.memory_bytes()) + "\n";
  for (const ResourcePart& p : e.memory) out += "    " + p.what + ": " + format_bytes(p.bytes) + "\n";
  char counts[128];
  std::snprintf(counts, sizeof counts, " (%.6g field snapshots, %.6g diagnostics samples, if the run goes to its end)",
                e.field_snapshots, e.diagnostics_samples);
  out += "  output run.h5 (estimate)  " + format_bytes(e.output_bytes()) + counts + "\n";
  for (const ResourcePart& p : e.output) out += "    " + p.what + ": " + format_bytes(p.bytes) + "\n";
  return out;
}

}  // namespace erythro::scene
