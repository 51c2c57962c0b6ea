#include "simulation/fields_recorder.hpp"

#include <stdexcept>

namespace erythro::sim {

const FieldsRecorder::Snapshot& FieldsRecorder::last() const {
  if (snapshots_.empty()) throw std::logic_error("FieldsRecorder: no field output was recorded");
  return snapshots_.back();
}

}  // namespace erythro::sim
