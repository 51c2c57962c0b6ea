#include "ib/kernel.hpp"

namespace erythro::ib {

std::string_view to_string(KernelType type) {
  switch (type) {
    case KernelType::cosine4: return "cosine4";
    case KernelType::peskin4: return "peskin4";
    case KernelType::roma3: return "roma3";
    case KernelType::linear2: return "linear2";
  }
  return "?";
}

bool parse_kernel(std::string_view name, KernelType& out) {
  for (KernelType t : kAllKernels) {
    if (name == to_string(t)) {
      out = t;
      return true;
    }
  }
  return false;
}

}  // namespace erythro::ib
