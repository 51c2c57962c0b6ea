#include "io/baseline_compare.hpp"

#include <cmath>
#include <functional>
#include <sstream>
#include <toml++/toml.h>

#include "common/error.hpp"
#include "io/h5.hpp"

namespace erythro::io {
namespace {

struct ToleranceTable {
  Tolerance fallback;
  std::map<std::string, Tolerance> by_quantity;

  Tolerance lookup(const std::string& path) const {
    const std::string name = path.substr(path.find_last_of('/') + 1);
    auto it = by_quantity.find(name);
    return it == by_quantity.end() ? fallback : it->second;
  }
};

Tolerance read_tolerance(const toml::table& t, const std::string& where) {
  Tolerance tol;
  for (auto&& [key, node] : t) {
    const auto value = node.value<double>();
    if (!value || *value < 0.0) throw InputError(where + "." + std::string(key.str()) + " must be a number >= 0");
    if (key == "atol") {
      tol.atol = *value;
    } else if (key == "rtol") {
      tol.rtol = *value;
    } else {
      throw InputError("unknown key '" + where + "." + std::string(key.str()) + "' (allowed: atol, rtol)");
    }
  }
  return tol;
}

ToleranceTable read_tolerances(const std::string& path) {
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw InputError(path + ":" + std::to_string(e.source().begin.line) + ": malformed TOML: " +
                     std::string(e.description()));
  }
  ToleranceTable table;
  for (auto&& [key, node] : root) {
    if (key == "default" && node.is_table()) {
      table.fallback = read_tolerance(*node.as_table(), path + ": default");
    } else if (key == "quantity" && node.is_table()) {
      for (auto&& [name, q] : *node.as_table()) {
        if (!q.is_table()) throw InputError(path + ": quantity." + std::string(name.str()) + " must be a table");
        table.by_quantity[std::string(name.str())] = read_tolerance(*q.as_table(), path + ": quantity." + std::string(name.str()));
      }
    } else {
      throw InputError(path + ": unknown key '" + std::string(key.str()) + "' (allowed: [default], [quantity.NAME])");
    }
  }
  return table;
}

// Visits every float dataset below `group`, depth first, with its full path.
void visit_datasets(hid_t group, const std::string& prefix, const std::function<void(const std::string&)>& visit) {
  for (const auto& name : h5::list(group)) {
    const std::string path = prefix + "/" + name;
    const hid_t object = H5Oopen(group, name.c_str(), H5P_DEFAULT);
    if (object < 0) continue;
    const H5I_type_t type_of_object = H5Iget_type(object);
    H5Oclose(object);
    if (type_of_object == H5I_GROUP) {
      h5::Handle sub = h5::open_group(group, name);
      visit_datasets(sub.id(), path, visit);
    } else if (type_of_object == H5I_DATASET) {
      h5::Handle set(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose);
      h5::Handle type(H5Dget_type(set.id()), H5Tclose);
      if (H5Tget_class(type.id()) == H5T_FLOAT) visit(path);
    }
  }
}

}  // namespace

bool BaselineReport::passed() const {
  for (const auto& d : datasets) {
    if (!d.passed) return false;
  }
  return !datasets.empty();
}

std::string BaselineReport::to_text() const {
  std::ostringstream out;
  out.precision(6);
  for (const auto& d : datasets) {
    out << (d.passed ? "same  " : "MOVED ") << d.path;
    if (!d.present) {
      out << ": missing or of another shape in the current file\n";
      continue;
    }
    out << ": max |diff| = " << d.max_abs_diff << ", max rel = " << d.max_rel_diff << " (atol " << d.tolerance.atol
        << ", rtol " << d.tolerance.rtol << ")";
    if (!d.passed) {
      out << "; worst at element " << d.worst_index << ": baseline " << d.worst_baseline << " -> current "
          << d.worst_current;
    }
    out << "\n";
  }
  if (datasets.empty()) out << "no float datasets in the baseline\n";
  out << (passed() ? "regression check: all quantities within tolerance\n" : "regression check: FAILED\n");
  return out.str();
}

BaselineReport compare_to_baseline(const std::string& current_h5, const std::string& baseline_h5,
                                   const std::string& tolerances_toml) {
  const ToleranceTable tolerances = read_tolerances(tolerances_toml);
  h5::Handle baseline = h5::open_file_read(baseline_h5);
  h5::Handle current = h5::open_file_read(current_h5);
  BaselineReport report;
  visit_datasets(baseline.id(), "", [&](const std::string& path) {
    DatasetComparison c;
    c.path = path;
    c.tolerance = tolerances.lookup(path);
    std::vector<hsize_t> base_dims, cur_dims;
    const std::vector<double> b = h5::read_dataset(baseline.id(), path, &base_dims);
    if (H5Lexists(current.id(), path.c_str(), H5P_DEFAULT) <= 0) {
      c.present = c.passed = false;
      report.datasets.push_back(c);
      return;
    }
    const std::vector<double> a = h5::read_dataset(current.id(), path, &cur_dims);
    if (cur_dims != base_dims) {
      c.present = c.passed = false;
      report.datasets.push_back(c);
      return;
    }
    double worst_excess = -1.0;
    for (std::size_t k = 0; k < b.size(); ++k) {
      const double diff = std::abs(a[k] - b[k]);
      const double allowed = c.tolerance.atol + c.tolerance.rtol * std::abs(b[k]);
      const bool bad = !(diff <= allowed);  // NaN counts as moved
      c.max_abs_diff = std::max(c.max_abs_diff, std::isnan(diff) ? INFINITY : diff);
      if (b[k] != 0.0) c.max_rel_diff = std::max(c.max_rel_diff, diff / std::abs(b[k]));
      const double excess = std::isnan(diff) ? INFINITY : diff - allowed;
      if (excess > worst_excess) {
        worst_excess = excess;
        c.worst_index = k;
        c.worst_baseline = b[k];
        c.worst_current = a[k];
      }
      if (bad) c.passed = false;
    }
    report.datasets.push_back(c);
  });
  return report;
}

}  // namespace erythro::io
