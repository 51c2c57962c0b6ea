#pragma once
// Reads a run.h5 written by io::RunWriter back (layout: run_writer.hpp): the diagnostics
// series by name, the profiles across the channel, metadata and per-stage timing, the
// cells' markers per field output.
// The V&V cases judge what this reads, so they judge what the writer wrote.
#include <map>
#include <string>
#include <vector>

namespace erythro::io {

class RunFile {
 public:
  struct CellsFrame {
    long step = 0;
    double time_s = 0.0;
    std::vector<double> x_um, y_um;  // all markers
    std::vector<std::size_t> offsets;  // cell c owns [offsets[c], offsets[c + 1])
    std::size_t cell_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  };

  RunFile() = default;
  // Throws OutputError naming the file if it cannot be read.
  explicit RunFile(const std::string& h5_path);

  bool has(const std::string& series) const { return series_.count(series) > 0; }
  // The series /diagnostics/<name>; throws std::out_of_range naming it if absent.
  const std::vector<double>& series(const std::string& name) const;
  std::size_t samples() const;
  bool has_profile(const std::string& name) const { return profiles_.count(name) > 0; }
  // The profile /profiles/<name>: one row per sample (that of /diagnostics/step[k]), one
  // value per lattice row; throws std::out_of_range naming it if absent.
  const std::vector<std::vector<double>>& profile(const std::string& name) const;
  // /profiles/y_um, the rows' centres (empty without profiles).
  const std::vector<double>& profile_y_um() const { return profile_y_um_; }
  // The profiles' names in the file (y_um left out), sorted.
  std::vector<std::string> profile_names() const;
  const std::string& status() const { return status_; }
  const std::string& diagnosis() const { return diagnosis_; }
  const std::string& scene_text() const { return scene_text_; }
  // /metadata: the build that wrote the file ("" if not said); the steps run and the wall time
  // (s) of a finished run (0 before its end).
  const std::string& git_revision() const { return git_revision_; }
  long steps() const { return steps_; }
  double wall_time_s() const { return wall_time_s_; }
  // Wall time (s) of a time-loop stage (/timing), 0 if the stage did not exist.
  double stage_seconds(const std::string& stage) const;
  const std::map<std::string, double>& timing() const { return timing_; }
  const std::vector<CellsFrame>& cells() const { return cells_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_, status_, diagnosis_, scene_text_, git_revision_;
  long steps_ = 0;
  double wall_time_s_ = 0.0;
  std::map<std::string, std::vector<double>> series_;
  std::map<std::string, std::vector<std::vector<double>>> profiles_;
  std::vector<double> profile_y_um_;
  std::map<std::string, double> timing_;
  std::vector<CellsFrame> cells_;
};

}  // namespace erythro::io
