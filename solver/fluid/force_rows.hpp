#pragma once
// The state of one row of a force field, kept per row by fluid::FluidLattice and honoured by
// the writers it hands the field to (ib::Transfer::spread). Clearing the field only marks
// its rows: a cleared row is zeroed by the writer right before its first addition to it
// (while the row is in the cache for those additions) or, if nobody writes it, at the start
// of the next fluid step. Every value read is that of a field zeroed when it was cleared
// (docs/performance-coupled-step.md, "The force field zeroed where it is written").
#include <cstdint>

namespace erythro::fluid::force_row {

inline constexpr std::uint8_t kZero = 0;     // every force in the row is zero
inline constexpr std::uint8_t kForced = 1;   // the row may hold force
inline constexpr std::uint8_t kCleared = 2;  // cleared, not yet zeroed: holds an earlier force that counts as zero

}  // namespace erythro::fluid::force_row
