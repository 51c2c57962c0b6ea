#include "app/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace erythro::app {
namespace {
void format_duration(double seconds, char* out, std::size_t size) {
  const long s = static_cast<long>(seconds + 0.5);
  std::snprintf(out, size, "%02ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
}
}  // namespace

ProgressDisplay::ProgressDisplay(bool quiet)
    : quiet_(quiet),
      terminal_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_ - std::chrono::seconds(1)) {}  // draw at the first step

void ProgressDisplay::on_progress(long step, long total, double mlups) {
  if (quiet_ || total <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (first_step_ < 0) first_step_ = step - 1;  // 0, or a restart's checkpoint step
  const double fraction = static_cast<double>(step) / static_cast<double>(total);
  const double done = static_cast<double>(step - first_step_) / static_cast<double>(total - first_step_);
  const double eta = done > 0.0 ? elapsed * (1.0 - done) / done : 0.0;
  char eta_text[32];
  format_duration(eta, eta_text, sizeof eta_text);
  if (terminal_) {
    if (step != total && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    std::fprintf(stderr, "\r  step %ld/%ld  %5.1f%%  %8.2f MLUPS  ETA %s ", step, total, 100.0 * fraction, mlups,
                 eta_text);
    std::fflush(stderr);
  } else if (100 * step >= next_percent_ * total) {
    std::fprintf(stderr, "step %ld/%ld (%.0f%%), %.2f MLUPS, ETA %s\n", step, total, 100.0 * fraction, mlups,
                 eta_text);
    while (100 * step >= next_percent_ * total) next_percent_ += 10;
  }
}

void ProgressDisplay::on_finish(const sim::RunSummary& summary) {
  if (quiet_) return;
  if (terminal_) std::fprintf(stderr, "\n");
  std::fprintf(stderr, "%s after %ld steps in %.2f s (%.2f MLUPS, %d threads)\n",
               sim::to_string(summary.status).c_str(), summary.steps, summary.wall_time_s, summary.mlups,
               summary.threads);
  if (summary.index_field_time_s > 0.0 && summary.wall_time_s > 0.0)
    std::fprintf(stderr, "index field: %.3f s, %.1f %% of the run; the step waited %.3f s for it (%.1f %%)\n",
                 summary.index_field_time_s, 100.0 * summary.index_field_time_s / summary.wall_time_s,
                 summary.index_field_exposed_time_s, 100.0 * summary.index_field_exposed_time_s / summary.wall_time_s);
  if (summary.index_field_rebuilds_beside_forces > 0)
    std::fprintf(
        stderr,
        "index field: %ld of its %ld rebuilds ran beside the force stage, the others before it (the faster kept)\n",
        summary.index_field_rebuilds_beside_forces, summary.index_field_rebuilds);
}

}  // namespace erythro::app
