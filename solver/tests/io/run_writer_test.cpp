// The run writer: a finished run and an aborted run both leave a valid file in
// place with their status; nothing is left under a temporary name; profiles are one row
// per sample.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/h5.hpp"
#include "io/run_file.hpp"
#include "io/run_writer.hpp"
#include "simulation/series_recorder.hpp"

using namespace erythro;

namespace {
scene::LatticeSetup small_setup() {
  scene::LatticeSetup s;
  s.grid = Grid{4, 3};
  s.scales = {1e-6, 1e-7, 1000.0};
  return s;
}
std::filesystem::path fresh_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}
}  // namespace

TEST(RunWriter, FinishedRunIsComplete) {
  const auto dir = fresh_dir("erythro_writer_ok");
  {
    io::RunWriter w(dir.string());
    scene::Scene scene;
    w.on_start(scene, small_setup());
    fluid::Moments m{std::vector<double>(12, 1.0), std::vector<double>(12, 0.1), std::vector<double>(12, 0.0)};
    const std::vector<sim::SeriesInfo> series = {{"step", "", ""}, {"total_mass_kg_per_m", "kg/m", "mass"}};
    w.on_series_declared(series);
    w.on_sample(0, std::vector<double>{0.0, 12.0});
    w.on_fields(0, m);
    sim::RunSummary summary;
    summary.steps = 0;
    w.on_finish(summary);
  }
  auto file = io::h5::open_file_read((dir / "run.h5").string());
  auto meta = io::h5::open_group(file.id(), "metadata");
  EXPECT_EQ(io::h5::read_attr_string(meta.id(), "status"), "completed");
  std::vector<hsize_t> dims;
  auto frame = io::h5::open_group(file.id(), "fields/0000000000");
  const auto velocity = io::h5::read_dataset(frame.id(), "velocity", &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{3, 4, 3}));  // x, y and a zero z component
  EXPECT_EQ(velocity[2], 0.0);
  EXPECT_DOUBLE_EQ(velocity[0], 0.1 * 10.0 * 1e6);  // lattice 0.1 × (h/Δt = 10 m/s) in µm/s
  EXPECT_TRUE(std::filesystem::exists(dir / "run.xdmf"));
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(e.path().string().find(".partial"), std::string::npos) << e.path();
  }
}

TEST(RunWriter, AbortedRunKeepsWhatWasWritten) {
  const auto dir = fresh_dir("erythro_writer_abort");
  {
    io::RunWriter w(dir.string());
    scene::Scene scene;
    w.on_start(scene, small_setup());
    const std::vector<sim::SeriesInfo> series = {{"step", "", ""}, {"total_mass_kg_per_m", "kg/m", "mass"}};
    w.on_series_declared(series);
    w.on_sample(0, std::vector<double>{0.0, 12.0});
    w.abort("disk full (simulated)");
  }
  auto file = io::h5::open_file_read((dir / "run.h5").string());
  auto meta = io::h5::open_group(file.id(), "metadata");
  EXPECT_EQ(io::h5::read_attr_string(meta.id(), "status"), "aborted: disk full (simulated)");
  auto diag = io::h5::open_group(file.id(), "diagnostics");
  EXPECT_EQ(io::h5::read_dataset(diag.id(), "total_mass_kg_per_m").size(), 1u);
  auto mass = H5Dopen2(diag.id(), "total_mass_kg_per_m", H5P_DEFAULT);
  EXPECT_EQ(io::h5::read_attr_string(mass, "units"), "kg/m");
  H5Dclose(mass);
}

TEST(RunWriter, RecordsTheCellPopulationsSeedAndPlacedCells) {
  const auto dir = fresh_dir("erythro_writer_populations");
  {
    io::RunWriter w(dir.string());
    scene::Scene scene;
    scene.cells.resize(3);  // one cell of the file's own, then two of the population
    scene.cells[1].center_um = {1.5, 2.5};
    scene.cells[2].center_um = {3.5, 4.5};
    scene.cells[2].angle_deg = 30.0;
    scene::CellPopulationSpec pop;
    pop.seed = 42;
    pop.area_fraction = 0.3;
    scene.cell_populations.push_back(pop);
    scene.population_placements.push_back({1, 2, 0.25});
    w.on_start(scene, small_setup());
    w.on_finish(sim::RunSummary{});
  }
  auto file = io::h5::open_file_read((dir / "run.h5").string());
  auto pop = io::h5::open_group(file.id(), "metadata/cell_populations/0");
  EXPECT_EQ(io::h5::read_attr_double(pop.id(), "seed"), 42.0);
  EXPECT_EQ(io::h5::read_attr_double(pop.id(), "target_area_fraction"), 0.3);
  EXPECT_EQ(io::h5::read_attr_double(pop.id(), "area_fraction"), 0.25);
  EXPECT_EQ(io::h5::read_attr_double(pop.id(), "first_cell"), 1.0);
  EXPECT_EQ(io::h5::read_attr_double(pop.id(), "cell_count"), 2.0);
  EXPECT_FALSE(io::h5::has_attr(pop.id(), "target_count"));
  for (const auto& [name, expected] : {std::pair{"center_x_um", std::vector<double>{1.5, 3.5}},
                                       std::pair{"center_y_um", std::vector<double>{2.5, 4.5}},
                                       std::pair{"angle_deg", std::vector<double>{0.0, 30.0}}}) {
    std::vector<double> values(2);
    const hid_t attr = H5Aopen(pop.id(), name, H5P_DEFAULT);
    ASSERT_GE(attr, 0) << name;
    EXPECT_GE(H5Aread(attr, H5T_NATIVE_DOUBLE, values.data()), 0);
    H5Aclose(attr);
    EXPECT_EQ(values, expected) << name;
  }
}

// /metadata records the aggregation strength in physical terms (docs/model.md eqs 4.7–4.8); the
// ratio to the viscous stress only when the scene has a wall-driven shear.
TEST(RunWriter, RecordsTheAggregationStrength) {
  for (const bool sheared : {true, false}) {
    const auto dir = fresh_dir("erythro_writer_aggregation");
    {
      io::RunWriter w(dir.string());
      scene::LatticeSetup setup = small_setup();
      setup.membrane.emplace();
      setup.membrane->aggregation = aggregation::MorseParameters{1e-3, 2.0, 0.5, 12.0};
      scene::AggregationStrength g;
      g.surface_energy_J_m2 = 1.3e-7;
      g.de_star = 5.0;
      g.peak_stress_Pa = 0.2496;
      if (sheared) {
        g.shear_rate_per_s = 100.0;
        g.adhesion_to_viscous_stress = 2.08;
      }
      setup.membrane->aggregation_strength = g;
      w.on_start(scene::Scene{}, setup);
      w.on_finish(sim::RunSummary{});
    }
    auto file = io::h5::open_file_read((dir / "run.h5").string());
    auto meta = io::h5::open_group(file.id(), "metadata");
    EXPECT_EQ(io::h5::read_attr_double(meta.id(), "aggregation_surface_energy_J_m2"), 1.3e-7);
    EXPECT_EQ(io::h5::read_attr_double(meta.id(), "aggregation_de_star"), 5.0);
    EXPECT_EQ(io::h5::read_attr_double(meta.id(), "aggregation_peak_adhesion_stress_Pa"), 0.2496);
    EXPECT_EQ(io::h5::has_attr(meta.id(), "aggregation_adhesion_to_viscous_stress"), sheared);
    EXPECT_EQ(io::h5::has_attr(meta.id(), "aggregation_shear_rate_1_s"), sheared);
    if (sheared) {
      EXPECT_EQ(io::h5::read_attr_double(meta.id(), "aggregation_adhesion_to_viscous_stress"), 2.08);
      EXPECT_EQ(io::h5::read_attr_double(meta.id(), "aggregation_shear_rate_1_s"), 100.0);
    }
  }
}

TEST(RunWriter, ProfilesAreOneRowPerSample) {
  // 300 samples (more than one buffered block of 256) of two profiles over the 3 rows:
  // /profiles/<name> is (300, 3), row k the sample of /diagnostics/step[k], read back by
  // io::RunFile and kept alike by sim::SeriesRecorder.
  const auto dir = fresh_dir("erythro_writer_profiles");
  const scene::LatticeSetup setup = small_setup();
  sim::SeriesRecorder recorder;
  {
    io::RunWriter w(dir.string());
    sim::ObserverList observers;
    observers.add(w);
    observers.add(recorder);
    scene::Scene scene;
    observers.on_start(scene, setup);
    const std::vector<sim::SeriesInfo> series = {{"step", "", ""}, {"time_s", "s", ""}};
    const std::vector<sim::ProfileInfo> profiles = {{"velocity_x_um_s", "um/s", "a"}, {"haematocrit", "", "b"}};
    observers.on_series_declared(series);
    observers.on_profiles_declared(profiles);
    for (long k = 0; k < 300; ++k) {
      const double s = static_cast<double>(k);
      observers.on_sample(k, std::vector<double>{s, s * 1e-7});
      observers.on_profiles(k, std::vector<double>{s, s + 0.25, s + 0.5, -s, -s - 0.25, -s - 0.5});
    }
    observers.on_finish(sim::RunSummary{});
  }
  const io::RunFile file((dir / "run.h5").string());
  EXPECT_EQ(file.profile_y_um(), (std::vector<double>{0.5, 1.5, 2.5}));  // (j + ½) h, h = 1 µm
  EXPECT_EQ(file.profile_names(), (std::vector<std::string>{"haematocrit", "velocity_x_um_s"}));
  const auto& u = file.profile("velocity_x_um_s");
  const auto& phi = file.profile("haematocrit");
  ASSERT_EQ(u.size(), 300u);
  ASSERT_EQ(phi.size(), 300u);
  for (std::size_t k = 0; k < 300; ++k) {
    const double s = file.series("step")[k];
    EXPECT_EQ(u[k], (std::vector<double>{s, s + 0.25, s + 0.5})) << k;
    EXPECT_EQ(phi[k], (std::vector<double>{-s, -s - 0.25, -s - 0.5})) << k;
  }
  EXPECT_EQ(recorder.profile("velocity_x_um_s"), u);
  EXPECT_EQ(recorder.profile("haematocrit"), phi);
  EXPECT_THROW(recorder.profile("nothing"), std::out_of_range);
  EXPECT_THROW(file.profile("nothing"), std::out_of_range);
  auto h5file = io::h5::open_file_read((dir / "run.h5").string());
  auto group = io::h5::open_group(h5file.id(), "profiles");
  std::vector<hsize_t> dims;
  io::h5::read_dataset(group.id(), "velocity_x_um_s", &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{300, 3}));
  auto dataset = io::h5::open_dataset(group.id(), "velocity_x_um_s");
  EXPECT_EQ(io::h5::read_attr_string(dataset.id(), "units"), "um/s");
}
