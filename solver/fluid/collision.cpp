#include "fluid/collision.hpp"

namespace erythro::fluid {

std::string_view to_string(CollisionModel model) {
  switch (model) {
    case CollisionModel::bgk: return "bgk";
    case CollisionModel::trt: return "trt";
    case CollisionModel::regularized: return "regularized";
  }
  return "?";
}

bool parse_collision_model(std::string_view name, CollisionModel& out) {
  for (CollisionModel m : {CollisionModel::bgk, CollisionModel::trt, CollisionModel::regularized}) {
    if (name == to_string(m)) {
      out = m;
      return true;
    }
  }
  return false;
}

}  // namespace erythro::fluid
