// unit.doublet_migration (CI): the doublet cases give their strength as
// aggregation.surface_energy_J_m2 = k·E_S0 since aggregation.de_star means γ / 2.6e-8 J/m²
// (docs/model.md eq 4.7). They used to give aggregation.de_star = k, read then as γ = k·E_S
// with E_S the scene's membrane.shear_modulus_dyn_cm (the old reading, kept as the documented
// alternative). This checks that the γ, and hence the lattice pair density and every doublet
// result, are the same bits as before. docs/validation-doublet.md.
#include <gtest/gtest.h>

#include <vector>

#include "aggregation/morse_units.hpp"
#include "common/scene_case.hpp"
#include "doublet_cases.hpp"
#include "doublet_scene.hpp"
#include "membrane/membrane_units.hpp"

using namespace erythro;

namespace {
// The former path (scene/cell_checks.cpp before the migration): γ = k·E_S with E_S as the scene
// states it, D_e = pair_density_for(γ, shape) in SI, then to lattice units.
double old_reading_gamma(double level, const scene::Scene& s) {
  return level * (s.membrane.value_or(scene::MembraneSpec{}).shear_modulus_dyn_cm * membrane::kDynPerCm);
}

double old_reading_lattice_De(double level, const scene::Scene& s, const scene::LatticeSetup& L) {
  const scene::AggregationSpec& a = *s.aggregation;
  aggregation::MorsePhysical p;
  p.r0_m = a.zero_force_distance_um * 1e-6;
  p.beta_per_m = a.decay_per_um * 1e6;
  p.cutoff_m = a.cutoff_um.value_or(a.zero_force_distance_um + 5.0 / a.decay_per_um) * 1e-6;
  const aggregation::MorseParameters shape{1.0, p.r0_m, p.beta_per_m, p.cutoff_m};
  p.De_Pa = aggregation::pair_density_for(old_reading_gamma(level, s), shape);
  return aggregation::to_lattice(p, {L.scales.length_m, L.scales.time_s, L.scales.density_kg_m3}).De;
}
}  // namespace

TEST(DoubletMigration, SurfaceEnergyIsTheOldReadingsBitForBit) {
  std::vector<vv::DoubletShearConfig> configs = {vv::ci_config(), vv::study_config()};
  for (const auto& cs : vv::deformability_cases()) configs.push_back(vv::deformability_config(cs));
  for (vv::DoubletShearConfig c : configs) {
    for (double level : {0.0, 0.25, 0.5, 1.0, 2.0}) {  // every level the cases and the exploration use
      c.old_reading_de_star = level;
      const vv::DoubletScene d = vv::doublet_scene(c);
      const scene::LatticeSetup L = scene::derive_lattice(d.scene);
      ASSERT_TRUE(d.scene.aggregation && d.scene.aggregation->surface_energy_J_m2 && L.membrane->aggregation);
      EXPECT_EQ(*d.scene.aggregation->surface_energy_J_m2, old_reading_gamma(level, d.scene)) << level;
      EXPECT_EQ(L.membrane->aggregation->De, old_reading_lattice_De(level, d.scene, L)) << level;
    }
  }
}

// The scene files as they stand (a run without overrides): doublet.toml is old-reading De* = 1,
// scenes/doublet_shear.toml old-reading De* = 2.
TEST(DoubletMigration, SceneFilesKeepTheirSurfaceEnergy) {
  for (const auto& [path, level] : {std::pair{"validation/doublet/doublet.toml", 1.0},
                                    std::pair{"scenes/doublet_shear.toml", 2.0}}) {
    const scene::Scene s = vv::case_scene(path);
    ASSERT_TRUE(s.aggregation && s.aggregation->surface_energy_J_m2) << path;
    EXPECT_EQ(*s.aggregation->surface_energy_J_m2, old_reading_gamma(level, s)) << path;
  }
}
