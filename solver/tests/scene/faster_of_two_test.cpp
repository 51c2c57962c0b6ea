// sim::FasterOfTwo (simulation/faster_of_two.hpp): the choice between two interchangeable
// arrangements by their measured times. Requirements: each runs once first; then the one with
// the smaller mean of its last two times runs; the other runs again after kFirstRetry runs of
// the faster, and each retry it loses doubles that wait (up to kLastRetry), while a retry it
// wins makes it the faster; one slow time of the faster is corrected by its next time. Times
// are made up here (the choice is a function of them alone).
#include "simulation/faster_of_two.hpp"

#include <gtest/gtest.h>

namespace erythro::sim {
namespace {

// Runs `n` times whatever next() says, with the given time of each arrangement; returns how
// many of them went to arrangement 1.
long run(FasterOfTwo& choice, long n, double time0, double time1) {
  long ones = 0;
  for (long i = 0; i < n; ++i) {
    const int a = choice.next();
    ones += a;
    choice.record(a, a == 0 ? time0 : time1);
  }
  return ones;
}

TEST(FasterOfTwo, TriesEachThenKeepsTheFasterAndRetriesTheOtherLessOften) {
  FasterOfTwo choice;
  EXPECT_EQ(choice.next(), 0);
  choice.record(0, 2.0);
  EXPECT_EQ(choice.next(), 1);
  choice.record(1, 1.0);
  // kFirstRetry runs of the faster (1), then one retry of 0.
  EXPECT_EQ(run(choice, FasterOfTwo::kFirstRetry, 2.0, 1.0), FasterOfTwo::kFirstRetry);
  EXPECT_EQ(choice.next(), 0);
  choice.record(0, 2.0);
  // Lost: the wait doubles.
  EXPECT_EQ(run(choice, 2 * FasterOfTwo::kFirstRetry, 2.0, 1.0), 2 * FasterOfTwo::kFirstRetry);
  EXPECT_EQ(choice.next(), 0);
  choice.record(0, 2.0);
  // Over a long run the retries settle at one per kLastRetry runs.
  const long n = 100 * FasterOfTwo::kLastRetry;
  const long retries = n - run(choice, n, 2.0, 1.0);
  EXPECT_GE(retries, 95);
  EXPECT_LE(retries, 105);
}

TEST(FasterOfTwo, FollowsAChangeAndForgivesOneSlowTime) {
  FasterOfTwo choice;
  choice.record(0, 1.0);
  choice.record(1, 2.0);
  choice.record(0, 1.0);
  // One slow time of 0: the mean of its last two, 1.5, still beats 1's 2.0.
  choice.record(0, 2.0);
  EXPECT_EQ(choice.next(), 0);
  // 0 has become slow (two slow times): 1 runs.
  choice.record(0, 3.0);
  EXPECT_EQ(choice.next(), 1);
}

TEST(FasterOfTwo, ARetryThatWinsTakesOver) {
  FasterOfTwo choice;
  choice.record(0, 1.0);
  choice.record(1, 2.0);
  EXPECT_EQ(run(choice, FasterOfTwo::kFirstRetry, 1.0, 2.0), 0);
  ASSERT_EQ(choice.next(), 1);  // the first retry
  choice.record(1, 0.5);        // its mean, 1.25, still loses to 0's 1.0: the wait doubles
  EXPECT_EQ(run(choice, 2 * FasterOfTwo::kFirstRetry, 1.0, 0.5), 0);
  ASSERT_EQ(choice.next(), 1);  // the second retry
  choice.record(1, 0.5);        // mean 0.5: it wins and runs from now on
  EXPECT_EQ(run(choice, 4, 1.0, 0.5), 4);
}

}  // namespace
}  // namespace erythro::sim
