#include "io/field_pictures.hpp"

#include <cmath>
#include <cstdio>

#include "io/h5.hpp"

namespace erythro::io {

std::vector<FieldPicture> last_field_pictures(const std::string& h5_path, const std::string& label) {
  h5::Handle file = h5::open_file_read(h5_path);
  h5::Handle grid = h5::open_group(file.id(), "grid");
  const int nx = static_cast<int>(h5::read_attr_double(grid.id(), "nx"));
  const int ny = static_cast<int>(h5::read_attr_double(grid.id(), "ny"));
  const double h = h5::read_attr_double(grid.id(), "spacing_um");
  h5::Handle fields = h5::open_group(file.id(), "fields");
  const std::vector<std::string> frames = h5::list(fields.id());
  if (frames.empty()) return {};
  const std::string frame_name = frames.back();
  h5::Handle frame = h5::open_group(fields.id(), frame_name);
  const double time_s = h5::read_attr_double(frame.id(), "time_s");

  FieldPicture base;
  base.nx = nx;
  base.ny = ny;
  for (int i = 0; i < nx; ++i) base.x.push_back((i + 0.5) * h);
  for (int j = 0; j < ny; ++j) base.y.push_back((j + 0.5) * h);
  if (h5::exists(file.id(), "cells")) {
    h5::Handle cells = h5::open_group(file.id(), "cells");
    if (h5::exists(cells.id(), frame_name)) {
      h5::Handle c = h5::open_group(cells.id(), frame_name);
      const std::vector<double> xy = h5::read_dataset(c.id(), "positions");
      const std::vector<double> offsets = h5::read_dataset(c.id(), "offsets");
      for (std::size_t k = 0; k + 1 < offsets.size(); ++k)
        base.membranes.emplace_back(xy.begin() + static_cast<long>(2 * offsets[k]),
                                    xy.begin() + static_cast<long>(2 * offsets[k + 1]));
    }
  }
  char when[64];
  std::snprintf(when, sizeof when, " at t = %.4g s", time_s);
  std::vector<FieldPicture> out;
  for (const std::string& name : h5::list(frame.id())) {
    if (name == "density") continue;
    FieldPicture p = base;
    const std::vector<double> v = h5::read_dataset(frame.id(), name);
    if (name == "velocity") {  // (ny, nx, 3) → |u|
      p.data.resize(static_cast<std::size_t>(nx) * ny);
      for (std::size_t n = 0; n < p.data.size(); ++n) p.data[n] = std::hypot(v[3 * n], v[3 * n + 1]);
      p.quantity = "|u|";
      p.unit = "um/s";
    } else {
      p.data = v;
      p.quantity = name;
      p.unit = "uM";
    }
    p.name = label + " " + (name == "velocity" ? "speed" : name);
    p.title = label + ": " + p.quantity + when;
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace erythro::io
