#pragma once
// Immersed-boundary kernels φ (docs/model.md §2): δ_h(x) = φ(x/h) φ(y/h) / h², h = 1.
//
// The kernel is chosen at run time (KernelType) but the transfer loops are
// templated on a kernel struct, so φ is inlined: dispatch() switches once per
// call, never per node.
//
//  cosine4 : thesis eq 24, φ(r) = ¼[1 + cos(πr/2)], |r| ≤ 2. Its 4-point sums
//            satisfy Σφ = 1, Σ_even φ = Σ_odd φ = ½ and Σφ² = 3/8 exactly, but NOT
//            the first moment Σ(r − j)φ = 0 (defect up to ≈ 0.0211; Peskin 2002,
//            Acta Numerica 11:479, §6).
//  peskin4 : Peskin 2002 §6 (standard 4-point), all of the above including the first moment.
//  roma3   : Roma, Peskin & Berger 1999 (J Comput Phys 153:509), |r| ≤ 3/2:
//            Σφ = 1, Σ(r − j)φ = 0, Σφ² = ½.
//  linear2 : the hat 1 − |r|, |r| ≤ 1: Σφ = 1, Σ(r − j)φ = 0.
#include <cmath>
#include <numbers>
#include <string_view>

namespace erythro::ib {

enum class KernelType { cosine4, peskin4, roma3, linear2 };

inline constexpr KernelType kAllKernels[] = {KernelType::cosine4, KernelType::peskin4, KernelType::roma3,
                                             KernelType::linear2};

std::string_view to_string(KernelType type);
bool parse_kernel(std::string_view name, KernelType& out);

// Kernel structs: width = number of nodes per direction the support covers;
// phi(r) for any real r (zero outside the support).
struct Cosine4 {
  static constexpr int width = 4;
  static double phi(double r) {
    const double a = std::abs(r);
    return a < 2.0 ? 0.25 * (1.0 + std::cos(0.5 * std::numbers::pi * a)) : 0.0;
  }
};

struct Peskin4 {
  static constexpr int width = 4;
  static double phi(double r) {
    const double a = std::abs(r);
    if (a < 1.0) return 0.125 * (3.0 - 2.0 * a + std::sqrt(1.0 + 4.0 * a - 4.0 * a * a));
    if (a < 2.0) return 0.125 * (5.0 - 2.0 * a - std::sqrt(-7.0 + 12.0 * a - 4.0 * a * a));
    return 0.0;
  }
};

struct Roma3 {
  static constexpr int width = 3;
  static double phi(double r) {
    const double a = std::abs(r);
    if (a < 0.5) return (1.0 + std::sqrt(1.0 - 3.0 * a * a)) / 3.0;
    if (a < 1.5) return (5.0 - 3.0 * a - std::sqrt(1.0 - 3.0 * (1.0 - a) * (1.0 - a))) / 6.0;
    return 0.0;
  }
};

struct Linear2 {
  static constexpr int width = 2;
  static double phi(double r) {
    const double a = std::abs(r);
    return a < 1.0 ? 1.0 - a : 0.0;
  }
};

// Calls f(KernelStruct{}) for the given type; one switch per call.
template <class F>
decltype(auto) dispatch(KernelType type, F&& f) {
  switch (type) {
    case KernelType::peskin4: return f(Peskin4{});
    case KernelType::roma3: return f(Roma3{});
    case KernelType::linear2: return f(Linear2{});
    case KernelType::cosine4: break;
  }
  return f(Cosine4{});
}

// Scalar access for diagnostics and tests (one switch per call: not for loops).
inline double phi(KernelType type, double r) {
  return dispatch(type, [r](auto k) { return decltype(k)::phi(r); });
}
inline int width(KernelType type) {
  return dispatch(type, [](auto k) { return decltype(k)::width; });
}

// First node index of the support of a kernel of the given width around a marker
// at coordinate X (nodes sit at i + ½): the width nodes i0 … i0 + width − 1 are the
// only ones with |X − (i + ½)| < width/2. i0 = ⌊X + ½ − width/2⌋.
// The floor is written as a truncation and a correction (t − [x < t], equal to ⌊x⌋ for every
// x in int's range): std::floor keeps GCC from vectorising a loop over markers unless
// floating-point traps are declared off.
inline int support_start(double X, int kernel_width) {
  const double x = X + 0.5 - 0.5 * kernel_width;
  const int t = static_cast<int>(x);
  return t - (x < t ? 1 : 0);
}

}  // namespace erythro::ib
