#include "app/commands.hpp"

#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <sstream>

#include "app/progress.hpp"
#include "app/resources.hpp"
#include "app/restart.hpp"
#include "analysis/profiles.hpp"
#include "common/error.hpp"
#include "io/atomic_file.hpp"
#include "io/baseline_compare.hpp"
#include "io/output_folder.hpp"
#include "io/run_dispersion.hpp"
#include "io/run_file.hpp"
#include "io/scene_run.hpp"
#include "scene/resource_estimate.hpp"
#include "scene/scene_parser.hpp"
#include "scene/units.hpp"
#include "simulation/interrupt.hpp"
#include "simulation/simulation.hpp"

namespace erythro::app {
namespace fs = std::filesystem;

namespace {

int report(int code, const std::string& message) {
  std::cerr << "erythro: error: " << message << "\n";
  return code;
}

// Runs `body`, mapping the project's error types to exit codes.
template <class Body>
int guarded(Body&& body) {
  try {
    return body();
  } catch (const InputError& e) {
    return report(exit_code::bad_input, e.what());
  } catch (const OutputError& e) {
    return report(exit_code::output_failure, e.what());
  } catch (const std::bad_alloc&) {  // e.g. a run started with --ignore-memory-check
    return report(exit_code::runtime_failure, "out of memory (`erythro check` shows the run's estimated memory)");
  } catch (const std::exception& e) {
    return report(exit_code::runtime_failure, std::string("internal error: ") + e.what());
  }
}

// eq 12.4b, one line per bin of the cells' heights.
void print_dispersion_across(const io::RunDispersionAcross& a) {
  const analysis::DispersionProfile& p = a.profile;
  std::printf("across the channel at lag %.6g s (%s; docs/model.md eq 12.4b):\n", p.lag,
              a.lag_from_msd ? "picked from the MSD: the diffusive window's first lag, else where the slope has "
                               "fallen to 1.2; --lag-s to choose"
                             : "--lag-s");
  std::printf("%12s %12s %10s %14s %14s\n", "y_from_um", "y_to_um", "pairs", "drift_um_s", "D_yy_um2_s");
  for (const analysis::DispersionBin& b : p.bins)
    std::printf("%12.6g %12.6g %10ld %14.6g %14.6g\n", b.y_from, b.y_to, b.pairs, b.drift, b.D);
}

// With the folder's lock held: removes what a killed run left (and says so), and refuses
// to overwrite an earlier run unless forced (the run writer then replaces run.h5 and
// run.xdmf together when the run ends); never deletes anything else.
void prepare_output_folder(const std::string& dir, bool force) {
  for (const std::string& note : io::remove_stale_partials(dir, force)) std::cerr << "erythro: " << note << "\n";
  for (const char* name : {"run.h5", "run.xdmf"}) {
    const fs::path p = fs::path(dir) / name;
    if (fs::exists(p) && !force) {
      throw OutputError("output '" + p.string() + "' already exists; use --force to overwrite it or --out to choose another folder");
    }
  }
}

// SIGINT (Ctrl-C) or SIGTERM during a run: the first asks the time loop to end the run
// after the step in progress (status interrupted, run.h5 closed and in place); a second,
// for a user who will not wait, exits at once, leaving run.h5.partial-<PID> for the next
// run into the folder to remove.
void on_interrupt_signal(int signal) {
  if (sim::interrupt_signal() != 0) ::_exit(exit_code::interrupted_base + signal);
  sim::request_interrupt(signal);
}

void install_interrupt_handlers() {
  struct sigaction action = {};
  action.sa_handler = on_interrupt_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // a write in progress resumes instead of failing with EINTR
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace

int run_command(const RunOptions& options) {
  return guarded([&] {
    if (options.scene_path.empty() && options.restart_dir.empty())
      throw InputError("run: give a scene file, or --restart DIR to continue a run");
    std::optional<Restart> restart;
    if (!options.restart_dir.empty()) restart.emplace(options);
    scene::Scene scene = restart ? restart->take_scene() : scene::load_scene(options.scene_path, options.overrides);
    const scene::LatticeSetup setup = scene::derive_lattice(scene);
    check_run_resources(scene::estimate_resources(scene, setup), options.scene_path, options.ignore_memory_check,
                        std::cerr);
    const std::string out_dir =
        restart ? restart->out_dir()
        : options.out_dir.empty() ? (fs::path("out") / fs::path(options.scene_path).stem()).string()
                                  : options.out_dir;
    io::ensure_writable_directory(out_dir);
    const io::OutputFolderLock lock(out_dir);  // held until the run's files are in place
    // Continuing in the interrupted run's folder replaces its run.h5 (set aside, its history
    // kept; before the stale partial files are removed: a killed run's history is one of them).
    const bool continues_in_place = restart && restart->set_aside_interrupted_run();
    prepare_output_folder(out_dir, options.force || continues_in_place);

    ProgressDisplay progress(options.quiet);
    install_interrupt_handlers();
    const io::SceneRunResult run =
        io::run_scene(std::move(scene), setup, out_dir, {&progress}, restart ? restart->restore() : nullptr);
    if (restart) std::cout << "restarted at step " << restart->step() << "; history "
                           << restart->carry_over_history(run.h5_path, run.xdmf_path) << "\n";
    std::cout << "results: " << run.h5_path << "\n" << "fields:  " << run.xdmf_path << "\n";
    if (run.summary.status == sim::RunStatus::stopped) std::cout << "stopped: " << run.summary.diagnosis << "\n";
    if (run.summary.status == sim::RunStatus::interrupted) {
      std::cerr << "erythro: " << run.summary.diagnosis << "; everything up to it is in " << run.h5_path << "\n";
      return exit_code::interrupted_base + sim::interrupt_signal();
    }
    if (run.summary.status == sim::RunStatus::diverged) {
      std::cerr << "erythro: " << run.summary.diagnosis << "\n"
                << "erythro: everything up to the last healthy output is in " << run.h5_path << "\n";
      return exit_code::diverged;
    }
    return exit_code::ok;
  });
}

int check_command(const std::string& scene_path, const std::vector<std::string>& overrides) {
  return guarded([&] {
    const scene::Scene scene = scene::load_scene(scene_path, overrides);
    const scene::LatticeSetup setup = scene::derive_lattice(scene);
    std::cout << scene::format_lattice_report(scene, setup)
              << scene::format_resource_report(scene::estimate_resources(scene, setup));
    return exit_code::ok;
  });
}

int compare_command(const std::string& current, const std::string& baseline, const std::string& tolerances) {
  return guarded([&] {
    const io::BaselineReport result = io::compare_to_baseline(current, baseline, tolerances);
    std::cout << "comparing " << current << " with baseline " << baseline << "\n" << result.to_text();
    return result.passed() ? exit_code::ok : exit_code::regression;
  });
}

int dispersion_command(const std::string& run_h5, double after_s, int across_bins, double lag_s) {
  return guarded([&] {
    const io::RunFile file(run_h5);
    const io::RunDispersion r = io::run_dispersion(file, run_h5, after_s);
    const analysis::Dispersion& d = r.result;
    const io::CentroidHeights& h = r.heights;
    std::printf(
        "transverse dispersion of %zu cells, %zu samples every %.6g s from t = %.6g s (docs/model.md eq 12.4)\n",
        h.y.size(), h.y.front().size(), h.dt_s, h.first_time_s);
    std::printf("%14s %16s %8s %10s\n", "lag_s", "msd_um2", "slope", "pairs");
    for (const analysis::MsdPoint& p : d.msd)
      std::printf("%14.6g %16.6g %8.3f %10ld\n", p.lag, p.msd, p.slope, p.pairs);
    if (d.found)
      std::printf("D_yy = %.6g um^2/s (diffusive window %.6g-%.6g s, slope within 1 +- 0.2)\n", d.D, d.lag_from, d.lag_to);
    else
      std::printf("D_yy: no diffusive window (no 4 consecutive lags with slope within 1 +- 0.2): run longer\n");
    if (across_bins > 0) print_dispersion_across(io::run_dispersion_across(file, run_h5, across_bins, lag_s, r));
    return exit_code::ok;
  });
}

int profiles_command(const std::string& run_h5, double after_s) {
  return guarded([&] {
    const io::RunFile file(run_h5);
    for (const char* name : {"velocity_x_um_s", "haematocrit", "cell_flux_um_s"})
      if (!file.has_profile(name))
        throw InputError(run_h5 + ": no profile /profiles/" + name + ": profiles are written for channel scenes "
                         "(walls at the bottom and top, periodic in x, a steady body force along x)");
    const std::vector<double>& time = file.series("time_s");
    const std::size_t first = analysis::first_sample_after(time, after_s);
    if (first == time.size())
    {
      std::ostringstream why;
      why << run_h5 << ": no sample at or after " << after_s << " s (the run's last is at "
          << (time.empty() ? 0.0 : time.back()) << " s)";
      throw InputError(why.str());
    }
    // eq 12.7: the trapezoidal time mean over the window
    const std::vector<double> u = analysis::time_average(time, file.profile("velocity_x_um_s"), after_s);
    const std::vector<double> phi = analysis::time_average(time, file.profile("haematocrit"), after_s);
    const std::vector<double> q = analysis::time_average(time, file.profile("cell_flux_um_s"), after_s);
    const std::vector<double>& y = file.profile_y_um();
    // Every line but the table's starts with '#': numpy.loadtxt or gnuplot read the output as is.
    std::printf("# profiles across the channel, time-averaged over %zu samples from t = %.6g s to %.6g s "
                "(docs/model.md eqs 12.6, 12.7)\n",
                time.size() - first, time[first], time.back());
    std::printf("# %10s %18s %12s %16s\n", "y_um", "velocity_x_um_s", "haematocrit", "cell_flux_um_s");
    for (std::size_t j = 0; j < y.size(); ++j) std::printf("%12.6g %18.8g %12.6g %16.8g\n", y[j], u[j], phi[j], q[j]);
    const analysis::ChannelHaematocrits h = analysis::channel_haematocrits(phi, q, u);
    std::printf("# tube haematocrit H_t = %.6g (row mean of the haematocrit)\n", h.tube);
    std::printf("# discharge haematocrit H_d = %.6g (the cells' flux over the flow)\n", h.discharge);
    return exit_code::ok;
  });
}

}  // namespace erythro::app
