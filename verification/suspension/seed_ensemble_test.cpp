// Cases verification.channel_seed_ensemble and verification.channel_seed_ensemble_30um (study): a
// channel suspension's settled statistics do not depend on the seed of its random placement,
// within their statistical error (issue 19 item 7: ensembles of seeds, confidence intervals
// reported).
//
// Requirement: the user's channel scene (scenes/rbc_channel.toml: case I RBCs at 2D haematocrit
// 0.3, [time_mapping] Re = 0.1), made smaller (a 20 µm channel at h = 0.4 µm, or the scene's own
// 30 µm one at its own h = 0.25 µm, 30 µm long) and run with four seeds for 400 strain units at
// the wall shear rate,
// gives time means over strain 200–400 of the relative apparent viscosity, the normalised
// cell-free layer and the discharge haematocrit that agree between the seeds within their
// statistical error: a one-way analysis of variance of the seeds' block means (four blocks of 50
// strain units each) gives F below the 99 % quantile of F with 3 and 12 degrees of freedom. The
// ensemble mean with its 95 % confidence interval (Student's t over the seeds) is reported for
// each, and the χ² homogeneity statistic beside F (informative).
// Reference: the statistics of a stationary random process (the seeds are independent samples
// of the same suspension); F and t quantiles from the standard tables.
//
// Why this design (docs/verification-suspension.md §8, "Longer runs"): runs of 400 strain units
// by hand with seeds 1–4 showed the placement's arrangement decaying over hundreds of strain units
// (100 strain units, window 50–100, could not pass), and block means correlated over tens of
// strain units (hence blocks of 50). The χ² test takes each seed's standard error, estimated from
// four blocks, as exact and so overstates disagreement; F does not. Because window, blocks and
// test were chosen after seeing seeds 1–4, the case runs seeds 5–8, which nobody had seen.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <string>
#include <vector>

#include "common/case_support.hpp"
#include "common/concurrent_runs.hpp"
#include "common/scene_case.hpp"
#include "common/channel_case.hpp"

using namespace erythro;

namespace {

constexpr const char* kScene = "scenes/rbc_channel.toml";
constexpr double kLengthUm = 30.0;
// The channel's lumen (wall to wall): 20 µm, five cell radii, where the seeds were found to
// settle into states of their own; 30 µm, the scene's own, to see whether a wider channel mixes.
// Seeds 5–8, not 1–4: those chose the design (above). In the 30 µm channel seed 8's placement
// jams (random sequential addition places 16 of 20 cells), so that channel takes the next seed
// that places, 9 (as at h = 0.4 µm; checked with `erythro check`).
// Resolution: the 20 µm channel at h = 0.4 µm (a/h = 9.8, 69 markers), where it passes; the 30 µm
// one at the scene's own h = 0.25 µm (110 markers, 0.70 h apart, as the scene and the validation
// ensembles): at h = 0.4 µm its seeds disagreed on η_rel and H_d (F = 7.7 and 14.2, one seed 8 %
// more viscous) and one cell's area drifted 1.05 %, which verification.channel_resolution puts
// down to the resolution (η_rel 18 % above its limit at 0.4 µm; one seed in four tears there).
// The placement gap is 0.4 µm in both (the scene's; at h = 0.25 µm the default h jams no sooner).
struct Channel {
  const char* case_name;
  double height_um;
  double spacing_um;
  long markers;
  std::array<long, 4> seeds;
};
constexpr Channel kNarrow{"verification.channel_seed_ensemble", 20.0, 0.4, 69, {5, 6, 7, 8}};
constexpr Channel kWide{"verification.channel_seed_ensemble_30um", 30.0, 0.25, 110, {5, 6, 7, 9}};
constexpr double kMinGapUm = 0.4;
constexpr double kWallShearRate = 400.0;  // 1/s: F = 2μγ̇_w/H
// The arrangement the placement starts from decays over hundreds of strain units (seeds 1–4 by
// hand: η_rel's spread over the seeds ±7 % over strain 50–100, ±5 % over 200–400): 400 strain
// units, the window 200–400.
constexpr double kStrain = 400.0, kSettled = 200.0;
constexpr int kBlocks = 4;  // block means of 50 strain units (the lateral motion's correlation)
// Quantiles: F_0.99 with 3 and 4 × (4 − 1) = 12 degrees of freedom, Student's t_0.975 with 3.
constexpr double kF99_3_12 = 5.953, kT975_3 = 3.182;
static_assert(std::tuple_size_v<decltype(Channel::seeds)> == 4 && kBlocks == 4,
              "the quantiles above are those of four seeds of four blocks");
constexpr double kSampleStrain = 0.05;

struct SeedRun : vv::ChannelSeries {
  long seed = 0;
};

SeedRun run_seed(const Channel& channel, long seed) {
  // Every 0.05 strain units; the placement gap h (with the default 2h random sequential addition
  // jams at 10 of 13 cells).
  char label[16];
  std::snprintf(label, sizeof label, "seed%ld", seed);
  SeedRun out;
  out.seed = seed;
  // A scene that cannot be set up (the placement jams, say) fails this seed in the record, with
  // the reason, instead of ending the case and losing the other seeds' runs.
  try {
    static_cast<vv::ChannelSeries&>(out) = vv::run_channel({.scene = kScene,
                                                            .length_um = kLengthUm,
                                                            .height_um = channel.height_um,
                                                            .spacing_um = channel.spacing_um,
                                                            .markers = channel.markers,
                                                            .seed = seed,
                                                            .min_gap_um = kMinGapUm,
                                                            .wall_shear_rate_per_s = kWallShearRate,
                                                            .strain = kStrain,
                                                            .sample_strain = kSampleStrain,
                                                            .checkpoint_interval_s = vv::kStudyCheckpointS},
                                                           channel.case_name, label);
  } catch (const std::exception& e) {
    out.completed = false;
    out.diagnosis = std::string("not run: ") + e.what();
  }
  return out;
}

using Estimate = vv::WindowEstimate;  // one seed: the mean of its block means and their standard error

// The case of one channel: four seeds, their settled estimates, the ensemble and its record.
void seed_ensemble(const Channel& channel) {
  vv::Stopwatch total;
  io::ResultRecord record(channel.case_name, "suspension");
  char height[16];
  std::snprintf(height, sizeof height, "%g", channel.height_um);
  std::string seeds;  // "5, 6, 7, 8"
  for (long s : channel.seeds) seeds += (seeds.empty() ? "" : ", ") + std::to_string(s);
  record.set_requirement(
      "The channel scene (case I RBCs, 2D haematocrit 0.3, time mapping Re = 0.1) in a " + std::string(height) +
      " um channel run with four seeds (" + seeds + ") for " + vv::fmt("%g", kStrain) + " strain units at the wall "
      "shear rate: the time means over " + vv::strain_window(kSettled, kStrain) + " of the relative apparent "
      "viscosity, the normalised cell-free layer and the discharge "
      "haematocrit agree between the seeds within their statistical error (one-way analysis of variance of the seeds' "
      "block means, four blocks of 50 strain units each: F below its 99 % quantile, 5.953 for 3 and 12 degrees of "
      "freedom); ensemble means with 95 % confidence intervals and the chi^2 homogeneity statistic reported; every "
      "cell's area within 1 %.");
  record.set_reference("Stationary random process: the seeds are independent samples of one suspension; F, chi^2 "
                       "and Student's t quantiles from the standard tables.");
  char resolution[64];
  std::snprintf(resolution, sizeof resolution, "h = %g um (%ld markers per cell)", channel.spacing_um,
                channel.markers);
  record.set_parameter("scene", "scenes/rbc_channel.toml with domain 30 x " + std::string(height) + " um, " +
                                    resolution + ", min_gap 0.4 um, F = 2 mu gamma_w / H "
                                    "(wall shear rate 400 1/s), " + vv::fmt("%g", kStrain / kWallShearRate) + " s (" +
                                    vv::fmt("%g", kStrain) + " strain units), seeds " + seeds +
                                    " (1-4 chose the window and the test)");
  std::vector<SeedRun> runs(channel.seeds.size());
  std::vector<std::function<void()>> jobs;
  for (std::size_t i = 0; i < channel.seeds.size(); ++i)
    jobs.push_back([&, i] { runs[i] = run_seed(channel, channel.seeds[i]); });
  vv::run_concurrently(jobs);

  // The record written and its metrics asserted, whichever way the case ends.
  auto finish = [&] {
    record.set_wall_time(total.seconds());
    record.write_to_results_dir();
    for (const auto& m : record.metrics())
      EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << ": " << m.tolerance_reason;
  };
  // A run the health monitor stopped, or whose scene could not be set up, fails the case with
  // its reason and leaves no window to compare: the record then holds how far each seed got.
  bool all_completed = true;
  for (const SeedRun& r : runs) {
    all_completed = all_completed && r.completed;
    record.add_metric({"completed_seed" + std::to_string(r.seed), "1 when the run reached its " + vv::fmt("%g", kStrain) + " strain units, 0 "
                       "when the health monitor stopped it or its scene could not be set up", "",
                       r.completed ? 1.0 : 0.0, 1.0, 0.0, io::Comparison::at_least,
                       r.completed ? "the statistics need the whole window" : "stopped: " + r.diagnosis});
  }
  if (!all_completed) {
    for (const SeedRun& r : runs)
      vv::add_channel_run(record, r, {{"seed", static_cast<double>(r.seed)}}, kSettled, kStrain, kBlocks,
                          "seed " + std::to_string(r.seed));
    finish();
    return;
  }

  struct Quantity {
    const char* name;
    const char* what;
    std::vector<double> SeedRun::*series;
  };
  const std::vector<Quantity> quantities = {
      {"relative_apparent_viscosity", "relative apparent viscosity U0/U (eq 12.1)", &SeedRun::eta},
      {"cell_free_layer_normalised", "normalised cell-free layer (eq 12.2)", &SeedRun::cfl},
      {"discharge_haematocrit", "discharge haematocrit (eq 12.3)", &SeedRun::hd}};
  std::vector<std::vector<Estimate>> per_seed(quantities.size());
  std::vector<std::vector<std::vector<double>>> blocks(quantities.size());  // [quantity][seed][block]
  for (std::size_t q = 0; q < quantities.size(); ++q)
    for (const SeedRun& r : runs) {
      per_seed[q].push_back(vv::block_estimate(r.strain, r.*quantities[q].series, kSettled, kStrain, kBlocks));
      blocks[q].push_back(vv::block_means(r.strain, r.*quantities[q].series, kSettled, kStrain, kBlocks));
    }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const SeedRun& r = runs[i];
    record.add_run({{"seed", static_cast<double>(r.seed)},
                    {"cells", static_cast<double>(r.cells)},
                    {"steps", static_cast<double>(r.steps)},
                    {"relative_apparent_viscosity", per_seed[0][i].mean},
                    {"relative_apparent_viscosity_se", per_seed[0][i].se},
                    {"cell_free_layer_normalised", per_seed[1][i].mean},
                    {"cell_free_layer_normalised_se", per_seed[1][i].se},
                    {"discharge_haematocrit", per_seed[2][i].mean},
                    {"discharge_haematocrit_se", per_seed[2][i].se},
                    {"max_area_change", r.max_area_change},
                    {"wall_time_s", r.wall_s}},
                   r.scene_text);
    record.add_metric({"area_change_seed" + std::to_string(r.seed), "largest |A/A0 - 1| over the run", "",
                       r.max_area_change, 0.01, 0.0, io::Comparison::at_most, "issue 19 item 6: the area within 1 %"});
  }
  for (std::size_t q = 0; q < quantities.size(); ++q) {
    const vv::SeedEnsemble e = vv::combine_seeds(per_seed[q], kT975_3);
    const vv::OneWayAnova anova = vv::one_way_anova(blocks[q]);
    const std::string n = quantities[q].name;
    record.add_metric({n + "_seed_homogeneity", std::string("F of a one-way analysis of variance of the seeds' block "
                       "means of the ") + quantities[q].what + " (3 and 12 degrees of freedom)", "", anova.F, kF99_3_12,
                       0.0, io::Comparison::at_most,
                       "the seeds differ no more than the scatter of their own block means allows (99 % quantile of "
                       "F(3, 12)): the result does not depend on the seed"});
    record.add_metric({n + "_chi2", std::string("chi^2 of the seeds' means of the ") + quantities[q].what +
                       " about their weighted mean", "", e.chi2, -std::numeric_limits<double>::infinity(), 0.0,
                       io::Comparison::at_least,
                       "informative: takes each seed's standard error, estimated from four blocks, as exact, so it "
                       "overstates disagreement (for comparison: the 99 % quantile of chi^2(3) is 11.345)"});
    record.add_metric({n + "_ensemble_mean", std::string("mean over the four seeds of the ") + quantities[q].what, "",
                       e.mean, -std::numeric_limits<double>::infinity(), 0.0, io::Comparison::at_least,
                       "informative: the 95 % confidence half-width is the next metric"});
    record.add_metric({n + "_ci95", "95 % confidence half-width of the ensemble mean (t_0.975 = 3.182 times the "
                       "standard error over the seeds)", "", e.ci95, -std::numeric_limits<double>::infinity(), 0.0,
                       io::Comparison::at_least, "informative"});
    std::printf("%-28s", n.c_str());
    for (const Estimate& x : per_seed[q]) std::printf(" %.4f+-%.4f", x.mean, x.se);
    std::printf("  ensemble %.4f +- %.4f (95 %%), F %.2f, chi2 %.2f\n", e.mean, e.ci95, anova.F, e.chi2);
  }
  for (const SeedRun& r : runs)
    std::printf("seed %ld: %ld cells, %ld steps, %.1f s\n", r.seed, r.cells, r.steps, r.wall_s);
  finish();
}

}  // namespace

TEST(ChannelSeedEnsemble, FourSeeds) { seed_ensemble(kNarrow); }

TEST(ChannelSeedEnsemble, FourSeedsWiderChannel) { seed_ensemble(kWide); }
