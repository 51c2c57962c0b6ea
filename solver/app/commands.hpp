#pragma once
// The `erythro` subcommands. Each returns the process exit code (docs/cli.md);
// errors are reported on stderr as "erythro: error: ...".
#include <string>
#include <vector>

namespace erythro::app {

struct RunOptions {
  std::string scene_path;
  std::string out_dir;  // default: out/<scene file stem>
  std::vector<std::string> overrides;
  bool force = false;   // overwrite an existing run in out_dir
  bool quiet = false;
  std::string restart_dir;  // --restart: continue the run of this folder (app/restart.hpp)
  bool ignore_memory_check = false;  // run even if the estimated memory exceeds what is available
};

int run_command(const RunOptions& options);
int check_command(const std::string& scene_path, const std::vector<std::string>& overrides);
int compare_command(const std::string& current, const std::string& baseline, const std::string& tolerances);
// `erythro dispersion RUN.h5`: the transverse dispersion of the cells from their centroid
// heights (analysis/dispersion.hpp), samples from `after_s` on; prints the MSD table and D_yy,
// and with `across_bins` > 0 the drift and dispersion across the channel in that many bins at
// the lag `lag_s` (0: picked from the MSD; analysis/dispersion_profile.hpp).
int dispersion_command(const std::string& run_h5, double after_s, int across_bins, double lag_s);
// `erythro profiles RUN.h5`: the profiles across a channel (/profiles) averaged over the
// samples from `after_s` on (analysis/profiles.hpp, eq 12.7); prints the table and H_t, H_d.
int profiles_command(const std::string& run_h5, double after_s);

}  // namespace erythro::app
