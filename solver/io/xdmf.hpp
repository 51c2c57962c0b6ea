#pragma once
// XDMF 2 index beside a run file so ParaView/VisIt open its fields. Paths inside
// are relative to the XDMF file, so the output folder can be moved.
#include <string>
#include <vector>

namespace erythro::io {

struct XdmfFrame {
  long step = 0;
  double time_s = 0.0;
  std::string group;  // e.g. "/fields/00000100"
};

struct XdmfGrid {
  int nx = 0, ny = 0;
  double spacing = 0.0;  // µm
  double origin_x = 0.0, origin_y = 0.0;
  std::vector<std::string> scalar_fields;  // dataset names inside each frame group
  std::vector<std::string> vector_fields;  // datasets of shape (ny, nx, 2)
};

std::string make_xdmf(const std::string& h5_file_name, const XdmfGrid& grid, const std::vector<XdmfFrame>& frames);

}  // namespace erythro::io
