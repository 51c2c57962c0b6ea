#pragma once
// A request from outside to end the run early: the command's SIGINT/SIGTERM handler
// records the signal here and returns; the time loop looks at it before every step and
// ends the run with status `interrupted`, so the step in progress is finished and the
// observers close their output cleanly. Process-wide, as signals are.
#include <string>

namespace erythro::sim {

// Async-signal-safe: only stores the number.
void request_interrupt(int signal) noexcept;
// The signal that asked for the interrupt, 0 if none did.
int interrupt_signal() noexcept;
// "SIGINT", "SIGTERM" or "signal <n>".
std::string signal_name(int signal);

}  // namespace erythro::sim
