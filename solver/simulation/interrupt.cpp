#include "simulation/interrupt.hpp"

#include <csignal>

namespace erythro::sim {
namespace {
// sig_atomic_t: the one type a signal handler may write and the program then read.
volatile std::sig_atomic_t requested_signal = 0;
}  // namespace

void request_interrupt(int signal) noexcept { requested_signal = signal; }

int interrupt_signal() noexcept { return requested_signal; }

std::string signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
  }
  return "signal " + std::to_string(signal);
}

}  // namespace erythro::sim
