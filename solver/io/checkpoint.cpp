#include "io/checkpoint.hpp"

#include <filesystem>

#include "common/build_info.hpp"
#include "common/error.hpp"
#include "io/atomic_file.hpp"
#include "io/h5.hpp"

namespace erythro::io {
namespace fs = std::filesystem;
namespace {

// Bumped when the layout or the meaning of an entry changes: an older checkpoint is refused.
constexpr long kFormat = 1;

void write_file(const std::string& path, const std::string& scene_text, long step, const StateRecord& state) {
  h5::Handle file = h5::create_file(path);
  h5::Handle meta = h5::create_group(file.id(), "metadata");
  h5::write_attrs(meta.id(), {{"step", step},
                              {"scene_text", scene_text},
                              {"format", kFormat},
                              {"erythro_version", build_info::version()},
                              {"git_revision", build_info::git_revision()}});
  h5::Handle group = h5::create_group(file.id(), "state");
  std::vector<std::string> empty;  // HDF5 writes no zero-length dataset or attribute
  for (const auto& [name, values] : state.arrays()) {
    if (values.empty()) empty.push_back(name);
    else h5::write_dataset(group.id(), name, values);
  }
  if (!empty.empty()) h5::write_attr(group.id(), "empty_entries", empty);
  h5::Handle texts = h5::create_group(file.id(), "texts");
  for (const auto& [name, text] : state.texts()) h5::write_attr(texts.id(), name, text);
}

// A 1-D attribute of variable-length strings (h5::write_attr of a vector of strings).
std::vector<std::string> read_string_list_attr(hid_t obj, const std::string& name) {
  h5::Handle attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose);
  h5::Handle space(attr.valid() ? H5Aget_space(attr.id()) : -1, H5Sclose);
  h5::Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (!space.valid() || H5Tset_size(type.id(), H5T_VARIABLE) < 0 || H5Tset_cset(type.id(), H5T_CSET_UTF8) < 0)
    throw OutputError("HDF5: cannot read attribute '" + name + "'");
  std::vector<char*> raw(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id())));
  if (!raw.empty() && H5Aread(attr.id(), type.id(), raw.data()) < 0)
    throw OutputError("HDF5: cannot read attribute '" + name + "'");
  std::vector<std::string> out;
  for (char* s : raw) {
    out.emplace_back(s ? s : "");
    H5free_memory(s);
  }
  return out;
}

Checkpoint read_file(const std::string& path) {
  Checkpoint c;
  c.path = path;
  h5::Handle file = h5::open_file_read(path);
  h5::Handle meta = h5::open_group(file.id(), "metadata");
  const long format = static_cast<long>(h5::read_attr_double(meta.id(), "format"));
  if (format != kFormat)
    throw InputError("checkpoint '" + path + "' has format " + std::to_string(format) + "; this erythro reads format " +
                     std::to_string(kFormat));
  c.step = static_cast<long>(h5::read_attr_double(meta.id(), "step"));
  c.scene_text = h5::read_attr_string(meta.id(), "scene_text");
  if (h5::has_attr(meta.id(), "git_revision")) c.git_revision = h5::read_attr_string(meta.id(), "git_revision");
  h5::Handle group = h5::open_group(file.id(), "state");
  for (const std::string& name : h5::list(group.id())) c.state.put(name, h5::read_dataset(group.id(), name));
  if (h5::has_attr(group.id(), "empty_entries"))
    for (const std::string& name : read_string_list_attr(group.id(), "empty_entries")) c.state.put(name, std::vector<double>{});
  h5::Handle texts = h5::open_group(file.id(), "texts");
  for (const std::string& name : h5::attribute_names(texts.id())) c.state.put_text(name, h5::read_attr_string(texts.id(), name));
  return c;
}

}  // namespace

void write_checkpoint(const std::string& out_dir, const std::string& scene_text, long step, const StateRecord& state) {
  const fs::path current = fs::path(out_dir) / kCheckpointName;
  const std::string temporary = temporary_path_for(current.string());
  write_file(temporary, scene_text, step, state);  // closed, so complete, before any rename
  std::error_code ec;
  if (fs::exists(current)) fs::rename(current, fs::path(out_dir) / kPreviousCheckpointName, ec);
  if (ec) throw OutputError("cannot keep the previous checkpoint '" + current.string() + "': " + ec.message());
  commit_temporary(current.string());
}

Checkpoint read_checkpoint(const std::string& dir) {
  std::string why;
  for (const char* name : {kCheckpointName, kPreviousCheckpointName}) {
    const fs::path path = fs::path(dir) / name;
    if (!fs::exists(path)) {
      why += "\n  " + path.string() + ": missing";
      continue;
    }
    try {
      return read_file(path.string());
    } catch (const InputError&) {
      throw;  // a readable checkpoint this erythro cannot use: say so rather than take an older one
    } catch (const std::exception& e) {
      why += "\n  " + path.string() + ": " + e.what();
    }
  }
  throw InputError("no readable checkpoint in '" + dir + "' (was the run given output.checkpoint_interval_steps or "
                   "output.checkpoint_interval_s?):" + why);
}

}  // namespace erythro::io
