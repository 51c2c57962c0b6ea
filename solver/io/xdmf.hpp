#pragma once
// The XDMF 2 index beside a run file, so that ParaView (its XDMF reader) and VisIt open
// the fields and the membranes. One temporal collection; each time step is a spatial
// collection of the fluid grid (a 3-D co-rectilinear mesh one node thick, in the x–y
// plane; density and species as scalars, velocity as a 3-component vector) and, with
// cells, the membranes (one closed polyline of edges per cell, a `cell` index per marker).
// Paths inside are relative to the XDMF file, so the output folder can be moved.
#include <string>
#include <vector>

namespace erythro::io {

struct XdmfFrame {
  long step = 0;
  double time_s = 0.0;
  std::string fields_group;  // e.g. "/fields/0000000100", "" if the step has no fields
  std::string cells_group;   // e.g. "/cells/0000000100", "" if it has no cells
  long markers = 0;          // markers (= edges) of all cells in cells_group
};

struct XdmfGrid {
  int nx = 0, ny = 0;
  double spacing = 0.0;  // µm
  double origin_x = 0.0, origin_y = 0.0;
  std::vector<std::string> scalar_fields;  // datasets (ny, nx) inside each fields group
  std::vector<std::string> vector_fields;  // datasets (ny, nx, 3)
};

std::string xdmf_header();
std::string xdmf_footer();
std::string xdmf_frame(const std::string& h5_file_name, const XdmfGrid& grid, const XdmfFrame& frame);
// The whole index: header, every frame, footer.
std::string make_xdmf(const std::string& h5_file_name, const XdmfGrid& grid, const std::vector<XdmfFrame>& frames);

}  // namespace erythro::io
