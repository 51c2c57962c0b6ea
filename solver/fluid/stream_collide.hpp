#pragma once
// The fused pull-scheme stream–collide kernel (internal to the fluid layer).
#include <cstddef>

#include "fluid/boundary.hpp"
#include "fluid/collision.hpp"
#include "lattice/grid.hpp"

namespace erythro::fluid::detail {

// How the kernel writes the destination lattice. Results are bitwise identical for
// every mode; only the memory traffic differs (docs/performance.md).
enum class StoreMode {
  automatic,  // streaming when both lattices exceed kStreamingFootprintBytes, else cached
  cached,     // ordinary stores (a lattice that fits in cache stays there)
  streaming,  // non-temporal stores: no write-allocate read of the destination
};

// Two lattices (144 B per node) larger than this do not stay in cache between steps,
// so the kernel streams its stores. Twice the 32 MiB L3 of the reference machine:
// measured, cached stores were 10 % faster at 512² (38 MB), equal at 640² (59 MB),
// and streaming stores 9–18 % faster from 768² (85 MB) on (docs/performance.md).
inline constexpr std::size_t kStreamingFootprintBytes = std::size_t{64} << 20;

struct KernelArgs {
  Grid grid;
  const double* src = nullptr;  // post-collision populations of step t, [q*N + n]
  double* dst = nullptr;        // post-collision populations of step t+1
  CollisionConfig collision;
  BoundaryConfig boundaries;
  const double* tau_field = nullptr;  // optional τ(x)
  const double* force_x = nullptr;    // optional F(x)
  const double* force_y = nullptr;
  double uniform_fx = 0.0, uniform_fy = 0.0;
  StoreMode stores = StoreMode::automatic;
};

void stream_collide(const KernelArgs& args);

// Whether stream_collide() uses non-temporal stores for this grid and mode.
bool uses_streaming_stores(const Grid& grid, StoreMode mode);

}  // namespace erythro::fluid::detail
