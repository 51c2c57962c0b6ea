#include "io/run_file.hpp"

#include <stdexcept>

#include "io/h5.hpp"

namespace erythro::io {

RunFile::RunFile(const std::string& h5_path) : path_(h5_path) {
  h5::Handle file = h5::open_file_read(h5_path);
  {
    h5::Handle meta = h5::open_group(file.id(), "metadata");
    status_ = h5::read_attr_string(meta.id(), "status");
    scene_text_ = h5::read_attr_string(meta.id(), "scene_text");
    if (h5::has_attr(meta.id(), "diagnosis")) diagnosis_ = h5::read_attr_string(meta.id(), "diagnosis");
    if (h5::has_attr(meta.id(), "git_revision")) git_revision_ = h5::read_attr_string(meta.id(), "git_revision");
    if (h5::has_attr(meta.id(), "steps")) steps_ = static_cast<long>(h5::read_attr_double(meta.id(), "steps"));
    if (h5::has_attr(meta.id(), "wall_time_s")) wall_time_s_ = h5::read_attr_double(meta.id(), "wall_time_s");
  }
  {
    h5::Handle diag = h5::open_group(file.id(), "diagnostics");
    for (const std::string& name : h5::list(diag.id())) series_[name] = h5::read_dataset(diag.id(), name);
  }
  if (h5::exists(file.id(), "profiles")) {
    h5::Handle group = h5::open_group(file.id(), "profiles");
    profile_y_um_ = h5::read_dataset(group.id(), "y_um");
    const std::size_t rows = profile_y_um_.size();
    for (const std::string& name : h5::list(group.id())) {
      if (name == "y_um" || rows == 0) continue;
      const std::vector<double> values = h5::read_dataset(group.id(), name);
      std::vector<std::vector<double>>& samples = profiles_[name];
      for (std::size_t k = 0; (k + 1) * rows <= values.size(); ++k)
        samples.emplace_back(values.begin() + static_cast<std::ptrdiff_t>(k * rows),
                             values.begin() + static_cast<std::ptrdiff_t>((k + 1) * rows));
    }
  }
  if (h5::exists(file.id(), "timing")) {
    h5::Handle timing = h5::open_group(file.id(), "timing");
    for (const std::string& name : h5::attribute_names(timing.id()))
      timing_[name] = h5::read_attr_double(timing.id(), name);
  }
  if (h5::exists(file.id(), "cells")) {
    h5::Handle cells = h5::open_group(file.id(), "cells");
    for (const std::string& name : h5::list(cells.id())) {
      h5::Handle frame = h5::open_group(cells.id(), name);
      CellsFrame f;
      f.step = static_cast<long>(h5::read_attr_double(frame.id(), "step"));
      f.time_s = h5::read_attr_double(frame.id(), "time_s");
      const std::vector<double> xy = h5::read_dataset(frame.id(), "positions");
      for (std::size_t m = 0; 2 * m + 1 < xy.size(); ++m) {
        f.x_um.push_back(xy[2 * m]);
        f.y_um.push_back(xy[2 * m + 1]);
      }
      for (double o : h5::read_dataset(frame.id(), "offsets")) f.offsets.push_back(static_cast<std::size_t>(o));
      cells_.push_back(std::move(f));
    }
  }
}

const std::vector<double>& RunFile::series(const std::string& name) const {
  const auto it = series_.find(name);
  if (it == series_.end()) throw std::out_of_range("run file " + path_ + ": no diagnostics series '" + name + "'");
  return it->second;
}

const std::vector<std::vector<double>>& RunFile::profile(const std::string& name) const {
  const auto it = profiles_.find(name);
  if (it == profiles_.end()) throw std::out_of_range("run file " + path_ + ": no profile '" + name + "'");
  return it->second;
}

std::vector<std::string> RunFile::profile_names() const {
  std::vector<std::string> names;
  for (const auto& [name, samples] : profiles_) names.push_back(name);
  return names;
}

std::size_t RunFile::samples() const { return series_.empty() ? 0 : series_.begin()->second.size(); }

double RunFile::stage_seconds(const std::string& stage) const {
  const auto it = timing_.find(stage + "_s");
  return it == timing_.end() ? 0.0 : it->second;
}

}  // namespace erythro::io
