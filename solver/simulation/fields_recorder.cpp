#include "simulation/fields_recorder.hpp"

#include <stdexcept>
#include <string>

namespace erythro::sim {

const FieldsRecorder::Snapshot& FieldsRecorder::last() const {
  if (snapshots_.empty()) throw std::logic_error("FieldsRecorder: no field output was recorded");
  return snapshots_.back();
}

const fluid::Moments& FieldsRecorder::at(long step) const {
  for (const Snapshot& s : snapshots_)
    if (s.step == step) return s.moments;
  throw std::logic_error("FieldsRecorder: no field output at step " + std::to_string(step));
}

}  // namespace erythro::sim
