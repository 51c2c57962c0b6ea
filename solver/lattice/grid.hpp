#pragma once
// A rectangular node grid, row-major: node (x, y) has index y*nx + x.
// Rows (fixed y) are the unit of OpenMP parallelism throughout erythro.
#include <cstddef>

namespace erythro {

struct Grid {
  int nx = 0;
  int ny = 0;

  std::size_t size() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(x);
  }
};

}  // namespace erythro
