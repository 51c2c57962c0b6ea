#include "simulation/stop_rule.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.hpp"

namespace erythro::sim {

StopRule::StopRule(const scene::StopWhenSpec& spec, std::size_t index, std::span<const SeriesInfo> series,
                   const std::string& scene_origin)
    : spec_(spec), rule_index_(index) {
  const auto it = std::find_if(series.begin(), series.end(), [&](const SeriesInfo& s) { return s.name == spec.series; });
  if (it == series.end()) {
    std::string names;
    for (const SeriesInfo& s : series) names += (names.empty() ? "" : ", ") + s.name;
    throw InputError(scene_origin + ": key 'stop_when[" + std::to_string(index) + "].series' = \"" + spec.series +
                     "\" names no diagnostics series of this scene (its series: " + names + ")");
  }
  column_ = static_cast<std::size_t>(it - series.begin());
}

bool StopRule::check(long step, std::span<const double> row) {
  const double v = row[column_];
  std::ostringstream why;
  bool holds = false;
  if (spec_.change_below && spec_.compare_window_means) {
    steps_.push_back(step);
    values_.push_back(v);
    // The samples in (step − W, step] against those in (step − 2W, step − W], once the history
    // reaches back to step − 2W.
    const long W = spec_.window_steps;
    if (steps_.front() <= step - 2 * W) {
      // A window without a sample (window_steps below the sampling interval) has no mean (NaN):
      // the condition does not hold.
      const double last = window_mean(step - W, step), before = window_mean(step - 2 * W, step - W);
      const double change = std::abs(last - before);
      holds = change < *spec_.change_below;
      why << "the mean of " << spec_.series << " over " << W << " steps changed by " << change << " < "
          << *spec_.change_below;
    }
  } else if (spec_.change_below) {
    // The latest earlier sample at least window_steps before this one.
    const auto at = std::upper_bound(steps_.begin(), steps_.end(), step - spec_.window_steps);
    if (at != steps_.begin()) {
      const std::size_t k = static_cast<std::size_t>(at - steps_.begin()) - 1;
      const double change = std::abs(v - values_[k]);
      holds = change < *spec_.change_below;
      why << spec_.series << " changed by " << change << " < " << *spec_.change_below << " over "
          << step - steps_[k] << " steps";
    }
    steps_.push_back(step);
    values_.push_back(v);
  } else if (spec_.below) {
    holds = v < *spec_.below;
    why << spec_.series << " = " << v << " < " << *spec_.below;
  } else if (spec_.above) {
    holds = v > *spec_.above;
    why << spec_.series << " = " << v << " > " << *spec_.above;
  }
  if (step < spec_.min_steps) return false;
  if (triggered_at_ < 0 && holds) {
    triggered_at_ = step;
    std::ostringstream d;
    d << "stop_when[" << rule_index_ << "]: " << why.str() << " at step " << step;
    if (spec_.after_steps > 0) d << ", then " << spec_.after_steps << " steps more";
    diagnosis_ = d.str();
  }
  return triggered_at_ >= 0 && step >= triggered_at_ + spec_.after_steps;
}

double StopRule::window_mean(long after, long up_to) const {
  const auto first = std::upper_bound(steps_.begin(), steps_.end(), after);
  const auto end = std::upper_bound(first, steps_.end(), up_to);
  double sum = 0.0;
  for (auto it = first; it != end; ++it) sum += values_[static_cast<std::size_t>(it - steps_.begin())];
  return end > first ? sum / static_cast<double>(end - first) : std::numeric_limits<double>::quiet_NaN();
}

void StopRule::save_state(StateRecord& r, const std::string& prefix) const {
  r.put(prefix + "steps", steps_);
  r.put(prefix + "values", values_);
  r.put_scalar(prefix + "triggered_at", static_cast<double>(triggered_at_));
  r.put_text(prefix + "diagnosis", diagnosis_);
}

void StopRule::restore_state(const StateRecord& r, const std::string& prefix) {
  steps_ = r.get_as<long>(prefix + "steps");
  values_ = r.get(prefix + "values");
  triggered_at_ = static_cast<long>(r.scalar(prefix + "triggered_at"));
  diagnosis_ = r.text(prefix + "diagnosis");
}

}  // namespace erythro::sim
