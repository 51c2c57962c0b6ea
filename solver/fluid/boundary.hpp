#pragma once
// Boundary condition per side of the rectangular domain.
//  periodic    : populations leaving one side enter the opposite side.
//  wall        : halfway bounce-back; the wall sits h/2 beyond the last node.
//  moving_wall : halfway bounce-back with the wall-momentum term of Ladd (1994),
//                f_ī(x, t+1) = f*_i(x, t) − 2 w_i ρ0 (c_i·u_w)/c_s², ρ0 = 1.
#include <string>
#include <string_view>

#include "geometry/domain.hpp"

namespace erythro::fluid {

enum class SideType { periodic, wall, moving_wall };

struct Side {
  SideType type = SideType::periodic;
  double ux = 0.0;  // wall velocity in lattice units (moving_wall only)
  double uy = 0.0;
};

struct BoundaryConfig {
  Side left, right, bottom, top;

  // Empty string when consistent; otherwise a sentence saying what is wrong
  // (a periodic side must face a periodic side; a moving wall moves tangentially).
  std::string inconsistency() const;
};

std::string_view to_string(SideType type);

// The domain of a fluid grid: an axis is periodic when its sides are (left/right for x,
// bottom/top for y; inconsistency() rejects a periodic side facing a wall).
inline geometry::Domain domain_of(const Grid& grid, const BoundaryConfig& b) {
  return {grid, b.left.type == SideType::periodic, b.bottom.type == SideType::periodic};
}
bool parse_side_type(std::string_view name, SideType& out);

}  // namespace erythro::fluid
