#pragma once
// A rectangular node grid, row-major: node (x, y) has index y*nx + x.
// Rows (fixed y) are the unit of OpenMP parallelism throughout erythro.
#include <cstddef>

namespace erythro {

struct Grid {
  int nx = 0;
  int ny = 0;

  std::size_t size() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }
  // Whether a loop over this grid should fork OpenMP threads: for small grids a
  // fork/join (and waiting for a descheduled worker on a loaded machine) costs
  // more than the work. Used as `#pragma omp parallel for if (grid.worth_threading())`.
  bool worth_threading() const { return size() >= 4096; }

  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(x);
  }
};

}  // namespace erythro
