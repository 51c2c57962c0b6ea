// The `erythro` command: run, check, compare, dispersion, profiles, bench, schema. Exit codes: docs/cli.md.
#include <CLI/CLI.hpp>
#include <iostream>

#include "app/bench.hpp"
#include "app/commands.hpp"
#include "app/schema_command.hpp"
#include "common/build_info.hpp"
#include "common/error.hpp"
#include "io/h5.hpp"

int main(int argc, char** argv) {
  using namespace erythro;
  io::h5::prepare_library();
  CLI::App cli{"erythro: red blood cells and NO/O2 transport in small arterioles (2D IB-LBM)"};
  cli.require_subcommand(0, 1);
  bool show_version = false;
  cli.add_flag("--version", show_version, "Print the version and git revision");

  app::RunOptions run;
  auto* run_cmd = cli.add_subcommand("run", "Run a scene and write OUT/run.h5 and OUT/run.xdmf");
  run_cmd->add_option("scene", run.scene_path, "Scene file (TOML); optional with --restart");
  run_cmd->add_option("--out", run.out_dir, "Output folder (default: out/<scene name>)");
  run_cmd->add_option("--set", run.overrides, "Override a scene key: --set fluid.tau=0.8 (repeatable)");
  run_cmd->add_flag("--force", run.force, "Overwrite an earlier run in the output folder");
  run_cmd->add_flag("--quiet", run.quiet, "No progress display");
  run_cmd->add_option("--restart", run.restart_dir,
                      "Continue the run whose output folder DIR holds a checkpoint (docs/cli.md)");
  run_cmd->add_flag("--ignore-memory-check", run.ignore_memory_check,
                    "Run even if the estimated memory exceeds the available memory");

  std::string check_scene;
  std::vector<std::string> check_overrides;
  auto* check_cmd = cli.add_subcommand("check", "Print the derived lattice parameters of a scene without running it");
  check_cmd->add_option("scene", check_scene, "Scene file (TOML)")->required();
  check_cmd->add_option("--set", check_overrides, "Override a scene key (repeatable)");

  std::string current, baseline, tolerances;
  auto* compare_cmd = cli.add_subcommand("compare", "Compare a run file with a regression baseline");
  compare_cmd->add_option("current", current, "Current run.h5")->required()->check(CLI::ExistingFile);
  compare_cmd->add_option("baseline", baseline, "Baseline .h5")->required()->check(CLI::ExistingFile);
  compare_cmd->add_option("--tolerances", tolerances, "Tolerance file (TOML)")->required()->check(CLI::ExistingFile);

  std::string dispersion_run;
  double dispersion_after_s = 0.0;
  auto* dispersion_cmd =
      cli.add_subcommand("dispersion", "Transverse dispersion D_yy of the cells of a finished run (docs/model.md §12)");
  dispersion_cmd->add_option("run", dispersion_run, "run.h5 of a run with cells")->required()->check(CLI::ExistingFile);
  dispersion_cmd->add_option("--after-s", dispersion_after_s, "Leave out the samples before this time (s)")
      ->check(CLI::Range(0.0, 1e30));
  int dispersion_bins = 0;
  double dispersion_lag_s = 0.0;
  auto* across_opt =
      dispersion_cmd
          ->add_option("--across", dispersion_bins,
                       "Also the drift and dispersion across the channel, in this many bins of the cells' heights")
          ->check(CLI::Range(1, 1000));
  dispersion_cmd
      ->add_option("--lag-s", dispersion_lag_s,
                   "The lag of --across (s), a whole number of sample intervals (default: from the MSD)")
      ->check(CLI::Range(0.0, 1e30))
      ->needs(across_opt);

  std::string profiles_run;
  double profiles_after_s = 0.0;
  auto* profiles_cmd = cli.add_subcommand(
      "profiles", "Time-averaged velocity and haematocrit profiles across a channel of a run (docs/model.md §12)");
  profiles_cmd->add_option("run", profiles_run, "run.h5 of a channel run")->required()->check(CLI::ExistingFile);
  profiles_cmd->add_option("--after-s", profiles_after_s, "Average from this time on (s): leave out the start-up")
      ->check(CLI::Range(0.0, 1e30));

  app::BenchOptions bench;
  auto* bench_cmd = app::add_bench_subcommand(cli, bench);

  app::SchemaOptions schema;
  auto* schema_cmd = app::add_schema_subcommand(cli, schema);

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? exit_code::ok : exit_code::bad_input;
  }
  if (show_version) {
    std::cout << "erythro " << build_info::version() << " (git " << build_info::git_revision() << ", "
              << build_info::compiler() << ")\n";
    return exit_code::ok;
  }
  if (*run_cmd) return app::run_command(run);
  if (*check_cmd) return app::check_command(check_scene, check_overrides);
  if (*compare_cmd) return app::compare_command(current, baseline, tolerances);
  if (*dispersion_cmd)
    return app::dispersion_command(dispersion_run, dispersion_after_s, dispersion_bins, dispersion_lag_s);
  if (*profiles_cmd) return app::profiles_command(profiles_run, profiles_after_s);
  if (*bench_cmd) return app::bench_command(bench);
  if (*schema_cmd) return app::schema_command(schema);
  std::cout << cli.help();
  return exit_code::bad_input;
}
