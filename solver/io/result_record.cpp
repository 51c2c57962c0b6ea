#include "io/result_record.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <set>

#include <sys/resource.h>

#include "common/build_info.hpp"
#include "io/atomic_file.hpp"
#include "io/h5.hpp"

namespace erythro::io {
namespace {
// User + system CPU time of this process so far, all threads: a case's CPU cost, which a
// loaded machine does not inflate as it does the wall time (and wall × cores ≥ CPU shows
// how well the case used its cores).
double process_cpu_seconds() {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0.0;
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(u.ru_utime) + seconds(u.ru_stime);
}
}  // namespace

std::string to_string(Comparison comparison) {
  switch (comparison) {
    case Comparison::absolute: return "absolute";
    case Comparison::relative: return "relative";
    case Comparison::at_most: return "at_most";
    case Comparison::at_least: return "at_least";
  }
  return "?";
}

bool Metric::passed() const {
  if (!std::isfinite(value)) return false;
  switch (comparison) {
    case Comparison::absolute: return std::abs(value - expected) <= tolerance;
    case Comparison::relative: return std::abs(value - expected) <= tolerance * std::abs(expected);
    case Comparison::at_most: return value <= expected;
    case Comparison::at_least: return value >= expected;
  }
  return false;
}

ResultRecord::ResultRecord(std::string case_name, std::string family)
    : case_name_(std::move(case_name)), family_(std::move(family)) {}

bool ResultRecord::add_metric(const Metric& metric) {
  metrics_.push_back(metric);
  return metric.passed();
}

bool ResultRecord::passed() const {
  if (metrics_.empty()) return false;
  for (const auto& m : metrics_) {
    if (!m.passed()) return false;
  }
  return true;
}

std::string ResultRecord::results_dir() {
  const char* env = std::getenv("ERYTHRO_RESULTS_DIR");
  std::string dir = (env && *env) ? env : "results";
  ensure_writable_directory(dir);
  return dir;
}

namespace {

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

void write_value_attr(hid_t obj, const std::string& key, const Value& value) {
  std::visit([&](const auto& v) { h5::write_attr(obj, key, v); }, value);
}

// HDF5 object names may not contain '/' or be '.'.
std::string safe_name(std::string name) {
  for (char& c : name) {
    if (c == '/') c = '_';
  }
  return name;
}

void write_runs(hid_t root, const std::vector<std::map<std::string, Value>>& runs) {
  h5::Handle group = h5::create_group(root, "runs");
  std::vector<std::string> columns;
  std::set<std::string> seen;
  for (const auto& row : runs) {
    for (const auto& [key, value] : row) {
      if (seen.insert(key).second) columns.push_back(key);
    }
  }
  std::vector<std::string> names;  // of the datasets, in column order
  for (const auto& column : columns) {
    names.push_back(safe_name(column));
    bool numeric = true;
    for (const auto& row : runs) {
      auto it = row.find(column);
      if (it != row.end() && !std::holds_alternative<double>(it->second)) numeric = false;
    }
    if (numeric) {
      std::vector<double> data;
      for (const auto& row : runs) {
        auto it = row.find(column);
        data.push_back(it == row.end() ? std::nan("") : std::get<double>(it->second));
      }
      h5::write_dataset(group.id(), names.back(), data);
    } else {
      std::vector<std::string> data;
      for (const auto& row : runs) {
        auto it = row.find(column);
        if (it == row.end()) {
          data.emplace_back("");
        } else if (std::holds_alternative<double>(it->second)) {
          data.push_back(std::to_string(std::get<double>(it->second)));
        } else {
          data.push_back(std::get<std::string>(it->second));
        }
      }
      h5::write_dataset(group.id(), names.back(), data);
    }
  }
  h5::write_attr(group.id(), "columns", names);
}

}  // namespace

void ResultRecord::add_run(std::map<std::string, Value> row, const std::string& scene_text) {
  auto it = std::find(scenes_.begin(), scenes_.end(), scene_text);
  if (it == scenes_.end()) it = scenes_.insert(scenes_.end(), scene_text);
  row["scene_index"] = static_cast<double>(it - scenes_.begin());
  runs_.push_back(std::move(row));
}

void ResultRecord::write(const std::string& path) const {
  try {
    h5::Handle file = h5::create_file(temporary_path_for(path));
    {  // the groups below are closed at the end of this block, before the file
      const hid_t root = file.id();
      h5::write_attrs(root, {{"schema_version", 1L},
                             {"case", case_name_},
                             {"family", family_},
                             {"requirement", requirement_},
                             {"reference", reference_},
                             {"verdict", passed() ? "pass" : "fail"},
                             {"git_revision", build_info::git_revision()},
                             {"compiler", build_info::compiler()},
                             {"compile_flags", build_info::compile_flags()},
                             {"created_utc", utc_now()},
                             {"wall_time_s", wall_time_s_},
                             {"cpu_time_s", process_cpu_seconds()}});

      h5::Handle params = h5::create_group(root, "parameters");
      for (const auto& [key, value] : parameters_) write_value_attr(params.id(), key, value);

      h5::Handle metrics = h5::create_group(root, "metrics");
      for (const auto& m : metrics_) {
        h5::Handle g = h5::create_group(metrics.id(), safe_name(m.name));
        h5::write_attrs(g.id(), {{"value", m.value},
                                 {"expected", m.expected},
                                 {"tolerance", m.tolerance},
                                 {"comparison", to_string(m.comparison)},
                                 {"tolerance_reason", m.tolerance_reason},
                                 {"description", m.description},
                                 {"unit", m.unit},
                                 {"verdict", m.passed() ? "pass" : "fail"}});
      }

      write_runs(root, runs_);

      h5::Handle conv = h5::create_group(root, "convergence");
      for (const auto& s : convergence_) {
        h5::Handle g = h5::create_group(conv.id(), safe_name(s.name));
        h5::write_dataset(g.id(), "h", s.h);
        h5::write_dataset(g.id(), "error", s.error);
        h5::write_dataset(g.id(), "local_orders", s.local_orders);
        h5::write_attrs(g.id(), {{"norm", s.norm},
                                 {"formal_order", s.formal_order},
                                 {"observed_order", s.observed_order},
                                 {"order_tolerance", s.order_tolerance},
                                 {"asymptotic", s.asymptotic ? 1L : 0L},
                                 {"asymptotic_rule", s.asymptotic_rule}});
      }

      h5::Handle speed = h5::create_group(root, "speed_error");
      for (const auto& s : speed_error_) {
        h5::Handle g = h5::create_group(speed.id(), safe_name(s.name));
        h5::write_dataset(g.id(), "wall_time_s", s.wall_time_s);
        h5::write_dataset(g.id(), "error", s.error);
        h5::write_dataset(g.id(), "label", s.label);
      }

      h5::Handle fields = h5::create_group(root, "fields");
      for (const auto& f : fields_) {
        h5::Handle g = h5::create_group(fields.id(), safe_name(f.name));
        h5::write_dataset(g.id(), "data", f.data, {static_cast<hsize_t>(f.ny), static_cast<hsize_t>(f.nx)});
        if (!f.x.empty()) h5::write_dataset(g.id(), "x", f.x);
        if (!f.y.empty()) h5::write_dataset(g.id(), "y", f.y);
        h5::write_attrs(g.id(), {{"title", f.title}, {"quantity", f.quantity}, {"unit", f.unit},
                                 {"xlabel", f.xlabel}, {"ylabel", f.ylabel}, {"name", f.name}});
        if (!f.membranes.empty()) {
          h5::Handle m = h5::create_group(g.id(), "membranes");
          for (std::size_t k = 0; k < f.membranes.size(); ++k)
            h5::write_dataset(m.id(), std::to_string(k), f.membranes[k], {f.membranes[k].size() / 2, 2});
        }
      }

      h5::Handle scenes = h5::create_group(root, "scenes");
      if (!scenes_.empty()) h5::write_dataset(scenes.id(), "texts", scenes_);

      h5::Handle series = h5::create_group(root, "series");
      for (const auto& s : series_) {
        h5::Handle g = h5::create_group(series.id(), safe_name(s.name));
        h5::write_dataset(g.id(), "x", s.x);
        h5::write_dataset(g.id(), "y", s.y);
        if (!s.y_reference.empty()) h5::write_dataset(g.id(), "y_reference", s.y_reference);
        h5::write_attrs(g.id(), {{"title", s.title},
                                 {"xlabel", s.xlabel},
                                 {"ylabel", s.ylabel},
                                 {"x_scale", std::string(s.log_x ? "log" : "linear")}});
      }
    }
    file.close();  // checked: the last metadata reaches the disk here
  } catch (...) {
    discard_temporary(path);
    throw;
  }
  commit_temporary(path);
}

std::string ResultRecord::write_to_results_dir() const {
  const std::string path = (std::filesystem::path(results_dir()) / (case_name_ + ".h5")).string();
  write(path);
  return path;
}

}  // namespace erythro::io
