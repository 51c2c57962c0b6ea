#pragma once
// Which of two interchangeable arrangements of a recurring piece of work to run next, chosen
// by their measured wall times. The two must give the same results (the caller's promise), so
// the choice moves only the time, never a bit; which one wins depends on the host and on the
// scene (docs/performance-coupled-step.md, "The index field beside or before the forces, by measurement").
//
// Each arrangement runs once first; then the one with the smaller mean of its last two times
// runs. The arrangement that runs is measured every time, so one slow time of it is corrected
// by its next. The other is run again after kFirstRetry runs of the faster, so that a change
// (cells gathering, the host's load) is noticed; each retry it loses doubles that wait, up to
// kLastRetry runs, which bounds what the retries cost once the answer is settled.
#include <algorithm>
#include <limits>

namespace erythro::sim {

class FasterOfTwo {
 public:
  static constexpr long kFirstRetry = 8, kLastRetry = 128;

  // 0 or 1: the arrangement to run next.
  int next() const {
    if (!measured(0)) return 0;
    if (!measured(1)) return 1;
    return countdown_ == 0 ? 1 - faster() : faster();
  }

  // The wall time (s) arrangement a (0 or 1) has just taken (the one next() returned).
  void record(int a, double seconds) {
    const bool both_before = measured(0) && measured(1);
    const bool retry = both_before && countdown_ == 0 && a != faster();
    Times& t = times_[a];
    t.before = t.last;
    t.last = seconds;
    ++t.count;
    if (!both_before) {
      countdown_ = wait_;  // from the run that measured both on: kFirstRetry runs, then a retry
    } else if (retry) {
      wait_ = faster() == a ? kFirstRetry : std::min(2 * wait_, kLastRetry);
      countdown_ = wait_;
    } else if (countdown_ > 0) {
      --countdown_;
    }
  }

  long runs(int a) const { return times_[a].count; }

 private:
  struct Times {
    double last = std::numeric_limits<double>::infinity(), before = std::numeric_limits<double>::infinity();
    long count = 0;
  };
  bool measured(int a) const { return times_[a].count > 0; }
  double mean(int a) const {
    const Times& t = times_[a];
    return t.count > 1 ? 0.5 * (t.last + t.before) : t.last;
  }
  int faster() const { return mean(1) < mean(0) ? 1 : 0; }

  Times times_[2];
  long wait_ = kFirstRetry, countdown_ = kFirstRetry;
};

}  // namespace erythro::sim
