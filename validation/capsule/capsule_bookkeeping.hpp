#pragma once
// The runs of the capsule-in-shear cases (validation.capsule_shear and its CI subset): each
// run's row in the record, the study's independent runs on the case's cores, and the sums
// behind the cost figures (issue 4 item 10).
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "capsule_run.hpp"
#include "io/result_record.hpp"

namespace erythro::vv {

struct CapsuleBookkeeping {
  io::ResultRecord& record;
  int capped = 0;           // runs that reached the strain cap before the stop rule
  int unsteady = 0;         // runs whose D changed by ≥ steady_drift between their last two strain units
  double max_area = 0;      // max |A/A0 − 1|
  double max_restored = 0;  // the largest area the projection gave back over a run, over A0
  double t_ib = 0, t_fluid = 0, marker_steps = 0, node_steps = 0;
  double t_forces = 0, t_zero = 0, t_spread = 0, t_moments = 0, t_move = 0;
  std::vector<double> run_markers = {}, run_marker_us = {};  // marker work per step (µs) against marker count
  std::map<std::string, CapsuleResult> prefetched = {};      // results of prefetch(), by label

  static std::string label_of(const CapsuleConfig& c, const std::string& role);

  // Runs a study's independent runs at once on the case's cores (run_concurrently: one OpenMP
  // thread each, the same bits as one after the other), the most expensive first; run() then
  // takes each result from here instead of running it again.
  void prefetch(const std::vector<std::pair<CapsuleConfig, std::string>>& plan);

  // The result of one run (prefetched, or run now), added to the record's runs and the sums.
  CapsuleResult run(const CapsuleConfig& c, const std::string& role);

  // The cost figures (parameters cost_*) from the sums over every run.
  void record_cost() const;
};

}  // namespace erythro::vv
