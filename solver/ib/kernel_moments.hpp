#pragma once
// Discrete moment sums of a kernel over the integer lattice (Peskin 2002, §6),
// for a marker at offset r from a node:  S_k(r) = Σ_j (r − j)^k φ(r − j).
// Used by the kernel unit tests and the verification.ib_kernels record.
#include "ib/kernel.hpp"

namespace erythro::ib {

struct MomentSums {
  double zeroth = 0;  // Σ φ            (partition of unity: 1)
  double first = 0;   // Σ (r − j) φ    (first moment: 0)
  double second = 0;  // Σ (r − j)² φ   (second moment; constant only for special kernels)
  double squares = 0; // Σ φ²           (Peskin's sum-of-squares condition: 3/8 for 4-point)
  double even = 0;    // Σ_{j even} φ   (even–odd condition: ½)
  double odd = 0;     // Σ_{j odd} φ
};

inline MomentSums moment_sums(KernelType type, double r) {
  MomentSums s;
  for (int j = -4; j <= 4; ++j) {
    const double d = r - j;
    const double p = phi(type, d);
    s.zeroth += p;
    s.first += d * p;
    s.second += d * d * p;
    s.squares += p * p;
    ((j % 2 == 0) ? s.even : s.odd) += p;
  }
  return s;
}

}  // namespace erythro::ib
