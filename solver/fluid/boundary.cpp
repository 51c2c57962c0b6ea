#include "fluid/boundary.hpp"

namespace erythro::fluid {

std::string_view to_string(SideType type) {
  switch (type) {
    case SideType::periodic: return "periodic";
    case SideType::wall: return "wall";
    case SideType::moving_wall: return "moving_wall";
  }
  return "?";
}

bool parse_side_type(std::string_view name, SideType& out) {
  for (SideType t : {SideType::periodic, SideType::wall, SideType::moving_wall}) {
    if (name == to_string(t)) {
      out = t;
      return true;
    }
  }
  return false;
}

std::string BoundaryConfig::inconsistency() const {
  const bool lr_periodic = left.type == SideType::periodic;
  if (lr_periodic != (right.type == SideType::periodic)) {
    return "left and right must both be periodic or both be walls";
  }
  if ((bottom.type == SideType::periodic) != (top.type == SideType::periodic)) {
    return "bottom and top must both be periodic or both be walls";
  }
  // Halfway bounce-back models an impermeable wall: the wall may only slide along itself.
  if ((bottom.type == SideType::moving_wall && bottom.uy != 0.0) ||
      (top.type == SideType::moving_wall && top.uy != 0.0)) {
    return "a bottom/top moving wall can only move along x (velocity y component must be 0)";
  }
  if ((left.type == SideType::moving_wall && left.ux != 0.0) ||
      (right.type == SideType::moving_wall && right.ux != 0.0)) {
    return "a left/right moving wall can only move along y (velocity x component must be 0)";
  }
  return {};
}

}  // namespace erythro::fluid
