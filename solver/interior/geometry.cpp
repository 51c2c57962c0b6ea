#include "interior/geometry.hpp"

#include "interior/index_field.hpp"

namespace erythro::interior {

double smoothed_heaviside(double d, double half_width) { return eq26(d, half_width); }

}  // namespace erythro::interior
