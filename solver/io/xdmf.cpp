#include "io/xdmf.hpp"

#include <sstream>

namespace erythro::io {

std::string xdmf_header() {
  return "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
         "<Xdmf Version=\"2.0\">\n <Domain>\n"
         "  <Grid Name=\"run\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
}

std::string xdmf_footer() { return "  </Grid>\n </Domain>\n</Xdmf>\n"; }

std::string xdmf_frame(const std::string& h5, const XdmfGrid& g, const XdmfFrame& f) {
  std::ostringstream x;
  x.precision(17);
  x << "   <Grid Name=\"step " << f.step << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
    << "    <Time Value=\"" << f.time_s << "\"/>\n";
  if (!f.fields_group.empty()) {
    // Dimensions, origin and spacing are slowest first: (z, y, x), one node in z; µm.
    x << "    <Grid Name=\"fluid\" GridType=\"Uniform\">\n"
      << "     <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"1 " << g.ny << " " << g.nx << "\"/>\n"
      << "     <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
      << "      <DataItem Format=\"XML\" NumberType=\"Float\" Precision=\"8\" Dimensions=\"3\">0 " << g.origin_y << " " << g.origin_x << "</DataItem>\n"
      << "      <DataItem Format=\"XML\" NumberType=\"Float\" Precision=\"8\" Dimensions=\"3\">" << g.spacing << " " << g.spacing << " " << g.spacing
      << "</DataItem>\n"
      << "     </Geometry>\n";
    for (const auto& name : g.scalar_fields)
      x << "     <Attribute Name=\"" << name << "\" AttributeType=\"Scalar\" Center=\"Node\">\n"
        << "      <DataItem Format=\"HDF\" NumberType=\"Float\" Precision=\"8\" Dimensions=\"1 " << g.ny << " " << g.nx
        << "\">" << h5 << ":" << f.fields_group << "/" << name << "</DataItem>\n     </Attribute>\n";
    for (const auto& name : g.vector_fields)
      x << "     <Attribute Name=\"" << name << "\" AttributeType=\"Vector\" Center=\"Node\">\n"
        << "      <DataItem Format=\"HDF\" NumberType=\"Float\" Precision=\"8\" Dimensions=\"1 " << g.ny << " " << g.nx
        << " 3\">" << h5 << ":" << f.fields_group << "/" << name << "</DataItem>\n     </Attribute>\n";
    x << "    </Grid>\n";
  }
  if (!f.cells_group.empty() && f.markers > 0) {
    x << "    <Grid Name=\"membranes\" GridType=\"Uniform\">\n"
      << "     <Topology TopologyType=\"Polyline\" NodesPerElement=\"2\" NumberOfElements=\"" << f.markers << "\">\n"
      << "      <DataItem Format=\"HDF\" NumberType=\"Int\" Precision=\"8\" Dimensions=\"" << f.markers << " 2\">" << h5
      << ":" << f.cells_group << "/edges</DataItem>\n"
      << "     </Topology>\n"
      << "     <Geometry GeometryType=\"XY\">\n"
      << "      <DataItem Format=\"HDF\" NumberType=\"Float\" Precision=\"8\" Dimensions=\"" << f.markers << " 2\">"
      << h5 << ":" << f.cells_group << "/positions</DataItem>\n"
      << "     </Geometry>\n"
      << "     <Attribute Name=\"cell\" AttributeType=\"Scalar\" Center=\"Node\">\n"
      << "      <DataItem Format=\"HDF\" NumberType=\"Int\" Precision=\"8\" Dimensions=\"" << f.markers << "\">" << h5
      << ":" << f.cells_group << "/cell</DataItem>\n"
      << "     </Attribute>\n"
      << "    </Grid>\n";
  }
  x << "   </Grid>\n";
  return x.str();
}

std::string make_xdmf(const std::string& h5, const XdmfGrid& grid, const std::vector<XdmfFrame>& frames) {
  std::string text = xdmf_header();
  for (const auto& f : frames) text += xdmf_frame(h5, grid, f);
  return text + xdmf_footer();
}

}  // namespace erythro::io
