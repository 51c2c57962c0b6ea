// [[stop_when]] with change_below: single samples against window means (scene.hpp StopWhenSpec,
// simulation/stop_rule.cpp), parsed from a scene's text as a user writes it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "scene/scene_parser.hpp"
#include "simulation/stop_rule.hpp"

using namespace erythro;

namespace {

scene::StopWhenSpec parse_rule(const std::string& rule) {
  const std::string text =
      "[domain]\nsize_um = [10, 10]\nspacing_um = 1.0\n[time]\ntau = 1.0\n"
      "[fluid]\ndensity_kg_m3 = 1000\nviscosity_cP = 1.0\n[run]\nsteps = 10\n"
      "[[stop_when]]\nseries = \"q\"\n" + rule;
  return scene::parse_scene(text, "rule.toml").stop_when.at(0);
}

const std::vector<sim::SeriesInfo> kSeries = {{"q", "", "a jittering quantity"}};

// q(step) = 1 + 0.01 (−1)^(step/10): a steady mean under a sample-to-sample jitter of 0.02,
// sampled every 10 steps. Returns the step at which the rule ends the run (−1: never).
long first_stop(const scene::StopWhenSpec& spec) {
  sim::StopRule rule(spec, 0, kSeries, "rule.toml");
  for (long step = 0; step <= 400; step += 10) {
    const double q = 1.0 + 0.01 * ((step / 10) % 2 == 0 ? 1.0 : -1.0);
    if (rule.check(step, std::vector<double>{q})) return step;
  }
  return -1;
}

}  // namespace

TEST(StopRule, SingleSamplesSeeTheJitter) {
  // Samples 50 steps apart (odd multiple of the period's half) always differ by 0.02.
  EXPECT_EQ(first_stop(parse_rule("change_below = 1e-3\nwindow_steps = 50\n")), -1);
}

TEST(StopRule, WindowMeansSeeTheSteadyMean) {
  // Windows of 20 steps hold two samples (one of each sign): equal means, so the rule holds as
  // soon as the history covers two windows (step 40), not earlier.
  const scene::StopWhenSpec spec = parse_rule("change_below = 1e-3\nwindow_steps = 20\ncompare = \"window_means\"\n");
  EXPECT_TRUE(spec.compare_window_means);
  EXPECT_EQ(first_stop(spec), 40);
}

TEST(StopRule, WindowMeansSeeADrift) {
  scene::StopWhenSpec spec = parse_rule("change_below = 1e-3\nwindow_steps = 20\ncompare = \"window_means\"\n");
  sim::StopRule rule(spec, 0, kSeries, "rule.toml");
  for (long step = 0; step <= 400; step += 10)  // q rises by 1e-3 per 10 steps: the means differ by 2e-3
    EXPECT_FALSE(rule.check(step, std::vector<double>{1e-4 * static_cast<double>(step)})) << step;
}

TEST(StopRule, WindowMeansNeedASampleInEachWindow) {
  // Windows of 5 steps between samples 10 steps apart: every other window is empty, so the rule
  // never holds (an empty window's mean is not 0).
  const scene::StopWhenSpec spec = parse_rule("change_below = 1e-3\nwindow_steps = 5\ncompare = \"window_means\"\n");
  sim::StopRule rule(spec, 0, kSeries, "rule.toml");
  for (long step = 0; step <= 400; step += 10) EXPECT_FALSE(rule.check(step, std::vector<double>{0.0})) << step;
}

TEST(StopRule, CompareIsOnlyForChangeBelow) {
  try {
    parse_rule("below = 0.5\ncompare = \"window_means\"\n");
    FAIL() << "accepted compare without change_below";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("stop_when[0].compare"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_rule("change_below = 1e-3\nwindow_steps = 20\ncompare = \"means\"\n"), InputError);
}
