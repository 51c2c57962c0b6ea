#include "io/run_history.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>

#include "common/error.hpp"
#include "io/atomic_file.hpp"
#include "io/h5.hpp"
#include "io/xdmf.hpp"

namespace erythro::io {
namespace {

// Replaces the chunked series `name` of `group` by `values` (its attributes stay): 1-D, or
// with `row_width` > 0 a profile of shape (samples, row_width).
void rewrite_series(hid_t group, const std::string& name, const std::vector<double>& values,
                    std::size_t row_width = 0) {
  h5::Handle dataset = h5::open_dataset(group, name);
  const hsize_t n[2] = {row_width > 0 ? values.size() / row_width : values.size(), row_width};
  if (H5Dset_extent(dataset.id(), n) < 0 ||
      (!values.empty() && H5Dwrite(dataset.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0))
    throw OutputError("HDF5: cannot rewrite the series " + name + " of the restarted run");
}

// The rows of the profiles (/profiles, one row per diagnostics sample) of `previous` before
// its first `keep` samples, by name (flattened, `row_width` values a row); empty with `why`
// set when they cannot be carried over.
std::map<std::string, std::vector<double>> profile_rows_before(hid_t previous, hid_t file, std::size_t keep,
                                                               std::size_t& row_width, std::string& why) {
  const bool old_has = h5::exists(previous, "profiles"), new_has = h5::exists(file, "profiles");
  if (old_has != new_has) {
    why = "its profiles differ from this run's";
    return {};
  }
  if (!new_has) return {};
  h5::Handle old_group = h5::open_group(previous, "profiles");
  h5::Handle new_group = h5::open_group(file, "profiles");
  const std::vector<std::string> names = h5::list(new_group.id());
  if (h5::list(old_group.id()) != names ||
      h5::read_dataset(old_group.id(), "y_um") != h5::read_dataset(new_group.id(), "y_um")) {
    why = "its profiles differ from this run's";
    return {};
  }
  row_width = h5::read_dataset(new_group.id(), "y_um").size();
  std::map<std::string, std::vector<double>> rows;
  for (const std::string& name : names) {
    if (name == "y_um") continue;
    std::vector<double> values = h5::read_dataset(old_group.id(), name);
    if (values.size() < keep * row_width) {  // cut short by a kill between two appends
      why = "its profile " + name + " is shorter than its step series";
      return {};
    }
    values.resize(keep * row_width);
    rows[name] = std::move(values);
  }
  return rows;
}

// Puts `rows` in front of each profile of `file`.
void prepend_profile_rows(hid_t file, const std::map<std::string, std::vector<double>>& rows, std::size_t row_width) {
  if (rows.empty()) return;
  h5::Handle group = h5::open_group(file, "profiles");
  for (const auto& [name, before] : rows) {
    std::vector<double> values = before;
    const std::vector<double> own = h5::read_dataset(group.id(), name);
    values.insert(values.end(), own.begin(), own.end());
    rewrite_series(group.id(), name, values, row_width);
  }
}

// The diagnostics samples of `previous` before `step`, by series name; empty with `why`
// set when they cannot be carried over.
std::map<std::string, std::vector<double>> samples_before(hid_t previous, hid_t file, long step, std::size_t& keep,
                                                          std::string& why) {
  h5::Handle old_group = h5::open_group(previous, "diagnostics");
  h5::Handle new_group = h5::open_group(file, "diagnostics");
  const std::vector<std::string> names = h5::list(new_group.id());
  if (h5::list(old_group.id()) != names) {
    why = "its diagnostics series differ from this run's";
    return {};
  }
  const std::vector<double> steps = h5::read_dataset(old_group.id(), "step");
  keep = static_cast<std::size_t>(std::lower_bound(steps.begin(), steps.end(), static_cast<double>(step)) -
                                  steps.begin());
  std::map<std::string, std::vector<double>> samples;
  for (const std::string& name : names) {
    std::vector<double> values = h5::read_dataset(old_group.id(), name);
    if (values.size() < keep) {  // a series cut short by a kill between two appends
      why = "its series " + name + " is shorter than its step series";
      return {};
    }
    values.resize(keep);
    samples[name] = std::move(values);
  }
  return samples;
}

// Puts `samples` in front of each series of `file`.
void prepend_samples(hid_t file, const std::map<std::string, std::vector<double>>& samples) {
  h5::Handle group = h5::open_group(file, "diagnostics");
  for (const auto& [name, before] : samples) {
    std::vector<double> values = before;
    const std::vector<double> own = h5::read_dataset(group.id(), name);
    values.insert(values.end(), own.begin(), own.end());
    rewrite_series(group.id(), name, values);
  }
}

// Copies the frames of group `name` (/fields or /cells) before `step` that `file` lacks.
void copy_frames(hid_t previous, hid_t file, const std::string& name, long step) {
  if (!h5::exists(previous, name) || !h5::exists(file, name)) return;
  h5::Handle from = h5::open_group(previous, name);
  h5::Handle to = h5::open_group(file, name);
  for (const std::string& frame : h5::list(from.id())) {
    if (std::stol(frame) >= step || h5::exists(to.id(), frame)) continue;
    if (H5Ocopy(from.id(), frame.c_str(), to.id(), frame.c_str(), H5P_DEFAULT, H5P_DEFAULT) < 0)
      throw OutputError("HDF5: cannot copy /" + name + "/" + frame + " into the restarted run's file");
  }
}

// The fields of every frame in the run writer's order: density, the species in scene order
// (/metadata species), velocity.
XdmfGrid xdmf_grid(hid_t file) {
  h5::Handle grid = h5::open_group(file, "grid");
  XdmfGrid g;
  g.nx = static_cast<int>(h5::read_attr_double(grid.id(), "nx"));
  g.ny = static_cast<int>(h5::read_attr_double(grid.id(), "ny"));
  g.spacing = h5::read_attr_double(grid.id(), "spacing_um");
  g.origin_x = g.origin_y = 0.5 * g.spacing;
  h5::Handle fields = h5::open_group(file, "fields");
  const std::vector<std::string> frames = h5::list(fields.id());
  if (frames.empty()) return g;
  h5::Handle first = h5::open_group(fields.id(), frames.front());
  std::vector<std::string> scalars{"density"};
  h5::Handle meta = h5::open_group(file, "metadata");
  if (h5::has_attr(meta.id(), "species")) {
    std::stringstream species(h5::read_attr_string(meta.id(), "species"));
    for (std::string name; std::getline(species, name, ',');) scalars.push_back(name);
  }
  for (const std::string& name : scalars)
    if (h5::exists(first.id(), name)) g.scalar_fields.push_back(name);
  if (h5::exists(first.id(), "velocity")) g.vector_fields.push_back("velocity");
  return g;
}

// run.xdmf for every frame of `file` (fields and cells), as the run writer writes it.
void rewrite_xdmf(hid_t file, const std::string& h5_path, const std::string& xdmf_path) {
  std::map<long, XdmfFrame> frames;
  auto frame_of = [&](hid_t group, const std::string& name) -> XdmfFrame& {
    XdmfFrame& f = frames[std::stol(name)];
    h5::Handle frame = h5::open_group(group, name);
    f.step = std::stol(name);
    f.time_s = h5::read_attr_double(frame.id(), "time_s");
    return f;
  };
  h5::Handle fields = h5::open_group(file, "fields");
  for (const std::string& name : h5::list(fields.id())) frame_of(fields.id(), name).fields_group = "/fields/" + name;
  if (h5::exists(file, "cells")) {
    h5::Handle cells = h5::open_group(file, "cells");
    for (const std::string& name : h5::list(cells.id())) {
      XdmfFrame& f = frame_of(cells.id(), name);
      f.cells_group = "/cells/" + name;
      h5::Handle frame = h5::open_group(cells.id(), name);
      f.markers = static_cast<long>(h5::read_dataset(frame.id(), "cell").size());
    }
  }
  std::vector<XdmfFrame> list;
  for (const auto& [step, f] : frames) list.push_back(f);
  const std::string h5_name = std::filesystem::path(h5_path).filename().string();
  write_text_atomically(xdmf_path, make_xdmf(h5_name, xdmf_grid(file), list));
}

}  // namespace

std::string carry_over_history(const std::string& previous_h5, const std::string& h5_path, const std::string& xdmf,
                               long checkpoint_step) {
  h5::Handle file = h5::open_file_read_write(h5_path);
  const std::string start = "starts at the checkpoint (step " + std::to_string(checkpoint_step) + ")";
  std::string note = previous_h5.empty() ? start + ": no earlier run.h5" : "carried over from " + previous_h5;
  if (!previous_h5.empty()) {
    std::string why;
    try {
      h5::Handle previous = h5::open_file_read(previous_h5);
      std::size_t keep = 0, row_width = 0;
      const auto samples = samples_before(previous.id(), file.id(), checkpoint_step, keep, why);
      const auto profile_rows =
          why.empty() ? profile_rows_before(previous.id(), file.id(), keep, row_width, why) : decltype(samples){};
      if (why.empty()) {
        prepend_samples(file.id(), samples);
        prepend_profile_rows(file.id(), profile_rows, row_width);
        copy_frames(previous.id(), file.id(), "fields", checkpoint_step);
        copy_frames(previous.id(), file.id(), "cells", checkpoint_step);
      }
    } catch (const OutputError& e) {  // e.g. a file cut short by a kill
      why = std::string("it cannot be carried over (") + e.what() + ")";
    }
    if (!why.empty()) note = start + ": " + previous_h5 + ": " + why;
  }
  h5::Handle meta = h5::open_group(file.id(), "metadata");
  h5::write_attrs(meta.id(), {{"restarted_from_step", checkpoint_step}, {"history", note}});
  meta.reset();
  rewrite_xdmf(file.id(), h5_path, xdmf);
  return note;
}

std::string interrupted_run_file(const std::string& dir) {
  namespace fs = std::filesystem;
  const fs::path finished = fs::path(dir) / "run.h5";
  if (fs::exists(finished)) return finished.string();
  fs::path newest;
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind("run.h5.partial-", 0) == 0 &&
        (newest.empty() || e.last_write_time() > fs::last_write_time(newest)))
      newest = e.path();
  if (newest.empty() && fs::exists(fs::path(dir) / kInterruptedRunName)) newest = fs::path(dir) / kInterruptedRunName;
  return newest.string();
}

std::string set_aside_interrupted_run(const std::string& file, const std::string& dir) {
  namespace fs = std::filesystem;
  if (file.empty()) return file;
  const fs::path aside = fs::path(dir) / kInterruptedRunName;
  if (fs::exists(aside) && fs::equivalent(file, aside)) return aside.string();
  std::error_code ec;
  fs::rename(file, aside, ec);
  if (ec)
    throw OutputError("cannot move the interrupted run's " + file + " to " + aside.string() + ": " + ec.message());
  return aside.string();
}

}  // namespace erythro::io
