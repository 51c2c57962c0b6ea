#pragma once
// Node marks shared by the index-field passes (index_field.cpp, band_pass.cpp, fill.cpp).
#include <cstdint>
#include <string>

#include "geometry/polygon.hpp"

namespace erythro::interior::detail {

inline constexpr std::uint8_t kFree = 0, kBand = 1, kFilled = 2;  // mark_ values

// "[x0, x1] x [y0, y1]" of the markers, for error messages.
std::string marker_box(const geometry::Polygon& p);

}  // namespace erythro::interior::detail
