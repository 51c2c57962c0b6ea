// analysis::time_average and channel_haematocrits (docs/model.md eq 12.7) on profiles whose
// answer is known: a profile linear in time over uneven samples (the trapezoids are exact:
// the mean is the value at the window's middle time), the window's start, one sample, the
// haematocrits of hand-made profiles, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "analysis/profiles.hpp"

using namespace erythro::analysis;

namespace {
// p_j(t) = a_j + b_j t at the given times, a_j = j, b_j = 1 + 2j.
std::vector<std::vector<double>> linear_rows(const std::vector<double>& time) {
  std::vector<std::vector<double>> rows;
  for (double t : time) rows.push_back({0.0 + 1.0 * t, 1.0 + 3.0 * t, 2.0 + 5.0 * t});
  return rows;
}
}  // namespace

TEST(ProfileAverage, LinearInTimeOverUnevenSamplesIsTheMiddleValue) {
  const std::vector<double> time{0.0, 0.1, 0.2, 0.3, 1.0, 2.0, 3.0, 3.5};  // dense start, off-interval end
  const auto rows = linear_rows(time);
  for (double after : {0.0, 0.15, 1.0}) {
    const std::size_t first = first_sample_after(time, after);
    const double middle = 0.5 * (time[first] + time.back());
    const std::vector<double> mean = time_average(time, rows, after);
    ASSERT_EQ(mean.size(), 3u);
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(mean[j], j + (1.0 + 2.0 * j) * middle, 1e-13) << after << " " << j;
  }
  // A plain mean of the samples would weigh the dense start: 8 samples, mean time 1.2625, not 1.75.
  EXPECT_NEAR(time_average(time, rows, 0.0)[0], 1.75, 1e-13);
}

TEST(ProfileAverage, WindowOfOneSampleIsThatSample) {
  const std::vector<double> time{0.0, 1.0, 2.0};
  const auto rows = linear_rows(time);
  EXPECT_EQ(time_average(time, rows, 1.5), rows[2]);
  EXPECT_EQ(first_sample_after(time, 1.0), 1u);
  EXPECT_EQ(first_sample_after(time, 2.5), 3u);
}

TEST(ProfileAverage, BadInputIsRefused) {
  const std::vector<double> time{0.0, 1.0, 2.0};
  EXPECT_THROW(time_average(time, linear_rows(time), 2.5), std::invalid_argument);  // empty window
  auto ragged = linear_rows(time);
  ragged[2].pop_back();
  EXPECT_THROW(time_average(time, ragged, 0.0), std::invalid_argument);
  EXPECT_THROW(time_average({0.0, 1.0, 1.0}, linear_rows(time), 0.0), std::invalid_argument);  // not increasing
  EXPECT_THROW(time_average(time, {{1.0}, {2.0}}, 0.0), std::invalid_argument);                // fewer rows
}

TEST(ChannelHaematocrits, TubeAndDischargeOfHandMadeProfiles) {
  // Four rows: cells fill the middle two half-way and move with the flow there.
  const std::vector<double> u{1.0, 3.0, 3.0, 1.0}, phi{0.0, 0.5, 0.5, 0.0}, q{0.0, 1.5, 1.5, 0.0};
  const ChannelHaematocrits h = channel_haematocrits(phi, q, u);
  EXPECT_DOUBLE_EQ(h.tube, 0.25);
  EXPECT_DOUBLE_EQ(h.discharge, 3.0 / 8.0);  // > H_t: the cells sit where the flow is fast
  EXPECT_TRUE(std::isnan(channel_haematocrits(phi, q, {0.0, 0.0, 0.0, 0.0}).discharge));
  EXPECT_THROW(channel_haematocrits(phi, q, {1.0}), std::invalid_argument);
}
