#include "io/xdmf.hpp"

#include <sstream>

namespace erythro::io {

std::string make_xdmf(const std::string& h5_file_name, const XdmfGrid& g, const std::vector<XdmfFrame>& frames) {
  std::ostringstream x;
  x.precision(17);
  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    << "<Xdmf Version=\"2.0\">\n <Domain>\n"
    << "  <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& f : frames) {
    x << "   <Grid Name=\"step " << f.step << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << f.time_s << "\"/>\n"
      // Dimensions are slowest first: (ny, nx). Origin and spacing likewise (y, x), in µm.
      << "    <Topology TopologyType=\"2DCoRectMesh\" Dimensions=\"" << g.ny << " " << g.nx << "\"/>\n"
      << "    <Geometry GeometryType=\"ORIGIN_DXDY\">\n"
      << "     <DataItem Format=\"XML\" Dimensions=\"2\">" << g.origin_y << " " << g.origin_x << "</DataItem>\n"
      << "     <DataItem Format=\"XML\" Dimensions=\"2\">" << g.spacing << " " << g.spacing << "</DataItem>\n"
      << "    </Geometry>\n";
    for (const auto& name : g.scalar_fields) {
      x << "    <Attribute Name=\"" << name << "\" AttributeType=\"Scalar\" Center=\"Node\">\n"
        << "     <DataItem Format=\"HDF\" NumberType=\"Float\" Precision=\"8\" Dimensions=\"" << g.ny << " " << g.nx
        << "\">" << h5_file_name << ":" << f.group << "/" << name << "</DataItem>\n    </Attribute>\n";
    }
    for (const auto& name : g.vector_fields) {
      x << "    <Attribute Name=\"" << name << "\" AttributeType=\"Vector\" Center=\"Node\">\n"
        << "     <DataItem Format=\"HDF\" NumberType=\"Float\" Precision=\"8\" Dimensions=\"" << g.ny << " " << g.nx
        << " 2\">" << h5_file_name << ":" << f.group << "/" << name << "</DataItem>\n    </Attribute>\n";
    }
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  return x.str();
}

}  // namespace erythro::io
