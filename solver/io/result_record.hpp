#pragma once
// The V&V result record: one HDF5 file per case, <results>/<case>.h5, read by
// reports/generate.py. The C++ test decides every verdict; the report only shows it.
//
// Layout (schema_version 1):
//   /                 attrs case, family, requirement, reference, verdict ("pass"|"fail"),
//                     git_revision, compiler, compile_flags, created_utc, wall_time_s,
//                     cpu_time_s (the process's user + system time when written), schema_version
//   /parameters       attrs: case-wide parameters (number or string)
//   /metrics/<name>   attrs value, expected, tolerance, comparison, tolerance_reason,
//                     description, unit, verdict
//   /runs/<column>    one dataset per column (float64 or string), one row per run;
//                     attr `columns`: string array of the dataset names, in order
//   /convergence/<s>  datasets h, error, local_orders; attrs norm, formal_order,
//                     observed_order, order_tolerance, asymptotic (0|1), asymptotic_rule
//   /speed_error/<s>  datasets wall_time_s, error, label
//   /series/<s>       datasets x, y (and y_reference if given); attrs xlabel, ylabel, title
//   /fields/<f>       data (ny, nx), x (nx), y (ny), membranes/<k> (n, 2); attrs title,
//                     quantity, unit, xlabel, ylabel: a field picture (add_field)
//   /scenes/texts     string dataset: the scene text (TOML after overrides) of every
//                     distinct scene the case ran; a run row's `scene_index` column
//                     names its entry (runs added with add_run(row, scene_text))
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace erythro::io {

// How a metric is judged.
enum class Comparison {
  absolute,  // |value − expected| ≤ tolerance
  relative,  // |value − expected| ≤ tolerance·|expected|
  at_most,   // value ≤ expected   (tolerance recorded for information, usually 0)
  at_least,  // value ≥ expected
};

struct Metric {
  std::string name;         // short identifier, e.g. "order_bgk_tau0.8"
  std::string description;  // one line for the report
  std::string unit;         // "" if dimensionless
  double value = 0.0;
  double expected = 0.0;
  double tolerance = 0.0;
  Comparison comparison = Comparison::absolute;
  std::string tolerance_reason;  // why this tolerance
  bool passed() const;
};

struct ConvergenceSeries {
  std::string name;       // e.g. "BGK tau=0.8"
  std::string norm;       // e.g. "relative L2 velocity"
  std::vector<double> h;  // grid spacing (lattice-independent: 1/N or h/L)
  std::vector<double> error;
  std::vector<double> local_orders;  // slope between successive resolutions
  double formal_order = 2.0;
  double observed_order = 0.0;  // least-squares slope of log(error) vs log(h)
  double order_tolerance = 0.0;
  bool asymptotic = false;
  std::string asymptotic_rule;  // how `asymptotic` was decided
};

struct SpeedErrorSeries {
  std::string name;  // e.g. "TRT"
  std::vector<double> wall_time_s;
  std::vector<double> error;
  std::vector<std::string> label;  // e.g. "N=64"
};

struct Series {
  std::string name, title, xlabel, ylabel;
  std::vector<double> x, y, y_reference;  // y_reference may be empty
  bool log_x = false;                      // the report draws x on a logarithmic axis
};

// A picture of a field for the report (docs/reports.md "Field pictures"): data[y][x]
// (row-major, ny × nx), cell-centre coordinates, membrane outlines on top.
struct FieldPicture {
  std::string name, title, quantity, unit, xlabel = "x (um)", ylabel = "y (um)";
  int nx = 0, ny = 0;
  std::vector<double> data, x, y;
  std::vector<std::vector<double>> membranes;  // each (n, 2) flattened: x0, y0, x1, y1, ...
};

using Value = std::variant<double, std::string>;

class ResultRecord {
 public:
  ResultRecord(std::string case_name, std::string family);

  void set_requirement(std::string text) { requirement_ = std::move(text); }
  void set_reference(std::string text) { reference_ = std::move(text); }
  void set_parameter(const std::string& key, Value value) { parameters_[key] = std::move(value); }

  // Adds a row to the /runs table; every row should have the same columns.
  void add_run(const std::map<std::string, Value>& row) { runs_.push_back(row); }
  // The same for a run of a scene: its text is kept once in /scenes and the row gets a
  // `scene_index` column pointing at it.
  void add_run(std::map<std::string, Value> row, const std::string& scene_text);
  // Texts of the scenes the case ran, in order of first use.
  const std::vector<std::string>& scenes() const { return scenes_; }
  // Adds a metric and returns whether it passed.
  bool add_metric(const Metric& metric);
  void add_convergence(const ConvergenceSeries& series) { convergence_.push_back(series); }
  void add_speed_error(const SpeedErrorSeries& series) { speed_error_.push_back(series); }
  void add_series(const Series& series) { series_.push_back(series); }
  void add_field(const FieldPicture& picture) { fields_.push_back(picture); }
  void set_wall_time(double seconds) { wall_time_s_ = seconds; }

  const std::string& case_name() const { return case_name_; }
  const std::vector<Metric>& metrics() const { return metrics_; }
  // A record passes when it has at least one metric and every metric passes.
  bool passed() const;

  // Writes the record atomically (temporary name, then rename); on a failed write
  // (disk full) throws OutputError and leaves neither the record nor its temporary.
  void write(const std::string& path) const;
  // Writes to results_dir()/<case>.h5 and returns that path.
  std::string write_to_results_dir() const;

  // $ERYTHRO_RESULTS_DIR, or "results" when unset; created if missing.
  static std::string results_dir();

 private:
  std::string case_name_, family_, requirement_, reference_;
  std::map<std::string, Value> parameters_;
  std::vector<std::map<std::string, Value>> runs_;
  std::vector<Metric> metrics_;
  std::vector<ConvergenceSeries> convergence_;
  std::vector<SpeedErrorSeries> speed_error_;
  std::vector<Series> series_;
  std::vector<std::string> scenes_;
  std::vector<FieldPicture> fields_;
  double wall_time_s_ = 0.0;
};

std::string to_string(Comparison comparison);

}  // namespace erythro::io
