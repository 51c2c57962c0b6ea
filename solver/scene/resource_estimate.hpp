#pragma once
// What a run will need before it starts (issue 17 part 5): the memory of its lattices and
// cells, and the volume of run.h5, estimated from the set-up's sizes alone (nothing is
// allocated). `erythro check` prints both; `erythro run` refuses a run that would not fit in
// the available memory and warns about a large output (app/resources.hpp).
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace erythro::scene {

struct ResourcePart {
  std::string what;  // "fluid populations (9 per node)"
  double bytes = 0.0;
};

struct ResourceEstimate {
  std::vector<ResourcePart> memory;  // the large arrays of the run, one line each
  std::vector<ResourcePart> output;  // run.h5: fields, cells, diagnostics
  double field_snapshots = 0.0;      // how many times the fields are written (at most)
  double diagnostics_samples = 0.0;  // how many diagnostics rows (at most)

  double memory_bytes() const;
  double output_bytes() const;
};

// Doubles are counted as the solver allocates them (fluid/fluid_lattice.hpp,
// transport/transport_lattice.hpp, interior/index_field.hpp, ...); small per-run state
// (tables, per-cell scalars) is left out. The output assumes the run goes to its last step
// (a steady state or a stop rule ends it earlier and writes less).
ResourceEstimate estimate_resources(const Scene& s, const LatticeSetup& L);

// "1.5 GB", "320 MB", "12 kB" (decimal units, three significant digits).
std::string format_bytes(double bytes);

// The lines `erythro check` prints: memory and output, each part and the total.
std::string format_resource_report(const ResourceEstimate& e);

}  // namespace erythro::scene
