// numeric::select_bits (common/select_bits.hpp), the choice the pair laws' vector loops make
// through the bits: the value of c ? a : b bit for bit, signed zeros, infinities, subnormals and
// NaN payloads included.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

#include "common/select_bits.hpp"

using erythro::numeric::select_bits;

TEST(SelectBits, GivesTheChosenValueBitForBit) {
  const std::vector<double> values = {0.0,
                                      -0.0,
                                      1.0,
                                      -2.5e-300,
                                      std::numeric_limits<double>::denorm_min(),
                                      -std::numeric_limits<double>::infinity(),
                                      std::numeric_limits<double>::infinity(),
                                      std::bit_cast<double>(std::uint64_t{0x7ff8000000000123}),  // NaN with a payload
                                      std::numeric_limits<double>::max()};
  for (double a : values) {
    for (double b : values) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(select_bits(true, a, b)), std::bit_cast<std::uint64_t>(a));
      EXPECT_EQ(std::bit_cast<std::uint64_t>(select_bits(false, a, b)), std::bit_cast<std::uint64_t>(b));
    }
  }
}
