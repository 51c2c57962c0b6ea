#include "simulation/field_recorder.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace erythro::sim {

void FieldRecorder::on_fields(long step, const fluid::Moments& moments) {
  if (step >= first_step_) frames_.push_back({step, moments});
}

bool FieldRecorder::has(long step) const {
  return std::any_of(frames_.begin(), frames_.end(), [&](const Frame& f) { return f.step == step; });
}

const fluid::Moments& FieldRecorder::at(long step) const {
  for (const Frame& f : frames_)
    if (f.step == step) return f.fields;
  throw std::out_of_range("FieldRecorder: no fields kept at step " + std::to_string(step));
}

const FieldRecorder::Frame& FieldRecorder::last() const {
  if (frames_.empty()) throw std::out_of_range("FieldRecorder: no fields were output");
  return frames_.back();
}

}  // namespace erythro::sim
