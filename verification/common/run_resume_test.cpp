// Unit tests of resumable case runs (run_resume.hpp, CaseRunOptions::resume): a run killed
// after a checkpoint continues from it to the uninterrupted run's series bit for bit, a finished
// run is read back, and another scene starts afresh; only a clean revision resumes. A small
// channel with cells (the product's scene), a few dozen steps.
#include "common/run_resume.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/channel_case.hpp"
#include "common/scene_case.hpp"
#include "io/result_record.hpp"
#include "scene/units.hpp"

using namespace erythro;

namespace {

constexpr const char* kCase = "unit.run_resume";

// The channel of `strain` strain units with a checkpoint every `checkpoint` steps.
scene::Scene channel(double strain, long diagnostics_interval, long checkpoint) {
  std::vector<std::string> o = vv::channel_overrides({.length_um = 30.0,
                                                      .height_um = 20.0,
                                                      .spacing_um = 0.4,
                                                      .markers = 69,
                                                      .seed = 5,
                                                      .wall_shear_rate_per_s = 200.0,
                                                      .strain = strain});
  o.push_back(vv::set("output.diagnostics_interval_steps", diagnostics_interval));
  o.push_back(vv::set("output.checkpoint_interval_steps", checkpoint));
  return vv::case_scene("scenes/rbc_channel.toml", o);
}

void expect_same_series(const io::RunFile& a, const io::RunFile& b) {
  ASSERT_GT(a.samples(), 5u);
  for (const char* name : {"step", "time_s", "relative_apparent_viscosity", "cell_free_layer_normalised",
                           "cells_max_area_change", "cells_max_edge_strain", "cell_0_centroid_y_um"}) {
    ASSERT_TRUE(a.has(name) && b.has(name)) << name;
    ASSERT_EQ(a.series(name).size(), b.series(name).size()) << name;
    for (std::size_t k = 0; k < a.series(name).size(); ++k)
      ASSERT_EQ(std::bit_cast<std::uint64_t>(a.series(name)[k]), std::bit_cast<std::uint64_t>(b.series(name)[k]))
          << name << " " << k;  // bit for bit, NaN samples included (η_rel before the flow is set up)
  }
  // The profiles across the channel, one row per sample (carried over row by row).
  ASSERT_FALSE(a.profile_names().empty());
  ASSERT_EQ(a.profile_names(), b.profile_names());
  for (const std::string& name : a.profile_names()) {
    ASSERT_EQ(a.profile(name).size(), b.profile(name).size()) << name;
    for (std::size_t k = 0; k < a.profile(name).size(); ++k)
      for (std::size_t j = 0; j < a.profile(name)[k].size(); ++j)
        ASSERT_EQ(std::bit_cast<std::uint64_t>(a.profile(name)[k][j]),
                  std::bit_cast<std::uint64_t>(b.profile(name)[k][j]))
            << name << " " << k << " " << j;
  }
}

}  // namespace

TEST(ResumableRun, OnlyACleanRevisionResumes) {
  EXPECT_TRUE(vv::revision_can_resume("8d5f18195bc7"));
  EXPECT_TRUE(vv::revision_can_resume("v1.2-3-g8d5f18195bc7"));
  EXPECT_FALSE(vv::revision_can_resume("8d5f18195bc7-dirty"));
  EXPECT_FALSE(vv::revision_can_resume("unknown"));
  EXPECT_FALSE(vv::revision_can_resume(""));
}

// In a clean build (CI's fresh clone): the killed run continues from its second checkpoint and
// is then read back. In a build with uncommitted changes, which never resumes: the same calls
// start afresh and say why. Either way every run ends with the uninterrupted run's series.
TEST(ResumableRun, ContinuesAKilledRunBitForBitAndReadsAFinishedOneBack) {
  const bool resumes = vv::build_can_resume();
  std::filesystem::remove_all(std::filesystem::path(io::ResultRecord::results_dir()) / "runs" / kCase);
  // About 90 steps: checkpoints at a third and two thirds, killed at five sixths.
  constexpr double kStrain = 0.02;
  const long steps = scene::derive_lattice(channel(kStrain, 5, 1)).total_steps;
  ASSERT_GE(steps, 30);
  ASSERT_LE(steps, 400);
  const long third = steps / 3, kill_at = 2 * third + third / 2;
  const scene::Scene scene = channel(kStrain, 5, third);
  const vv::CaseRun reference = vv::run_case_scene(scene, kCase, "reference");
  ASSERT_TRUE(reference.ok());

  // Killed (a stage that throws) after the checkpoints of steps `third` and 2 `third`.
  vv::CaseRunOptions killed;
  killed.resume = true;
  killed.configure = [kill_at](sim::Simulation& s) {
    s.add_stage(sim::Phase::prepare, "kill", [kill_at](long step) {
      if (step == kill_at) throw std::runtime_error("killed");
    });
  };
  EXPECT_THROW(vv::run_case_scene(scene, kCase, "resumed", killed), std::runtime_error);

  vv::CaseRunOptions resume;
  resume.resume = true;
  const vv::CaseRun continued = vv::run_case_scene(scene, kCase, "resumed", resume);
  EXPECT_EQ(continued.resumed_from_step, resumes ? 2 * third : -1) << continued.resume_note;
  if (!resumes) {
    EXPECT_NE(continued.resume_note.find("not clean"), std::string::npos) << continued.resume_note;
  }
  EXPECT_FALSE(continued.read_back);
  ASSERT_TRUE(continued.ok());
  expect_same_series(reference.file, continued.file);

  const vv::CaseRun again = vv::run_case_scene(scene, kCase, "resumed", resume);
  EXPECT_EQ(again.read_back, resumes) << again.resume_note;
  EXPECT_EQ(again.summary.steps, continued.summary.steps);
  expect_same_series(reference.file, again.file);

  // Another scene text in the same folder: neither read back nor continued.
  const vv::CaseRun other = vv::run_case_scene(channel(kStrain, 10, third), kCase, "resumed", resume);
  EXPECT_FALSE(other.read_back);
  EXPECT_EQ(other.resumed_from_step, -1) << other.resume_note;
  ASSERT_TRUE(other.ok());
  std::filesystem::remove_all(std::filesystem::path(io::ResultRecord::results_dir()) / "runs" / kCase);
}
