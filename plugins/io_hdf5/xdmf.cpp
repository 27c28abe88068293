#include "xdmf.hpp"

#include <fmt/format.h>

namespace bhnsid::io_hdf5 {

std::string viewer_name(const std::string& dataset_path) {
  const std::string name = dataset_path.substr(dataset_path.rfind('/') + 1);
  return dataset_path.rfind("/variables/", 0) == 0 ? "bhnsid_" + name : name;
}

std::string xdmf_text(const DataFile& file, const std::string& h5_name) {
  const Geometry& g = file.geometry;
  const std::string dims = fmt::format("{} {} {}", g.nz, g.ny, g.nx);
  // XDMF 2 orders the origin and the spacing of ORIGIN_DXDYDZ as z, y, x, like the dimensions.
  std::string out = fmt::format(
      "<?xml version=\"1.0\" ?>\n"
      "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      "<Xdmf Version=\"2.0\">\n"
      " <Domain>\n"
      "  <Grid Name=\"bhnsid\" GridType=\"Uniform\">\n"
      "   <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"{}\"/>\n"
      "   <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
      "    <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">{:.17g} {:.17g} {:.17g}</DataItem>\n"
      "    <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">{:.17g} {:.17g} {:.17g}</DataItem>\n"
      "   </Geometry>\n",
      dims, g.origin[2], g.origin[1], g.origin[0], g.dx, g.dx, g.dx);
  for (const std::string& path : file.datasets)
    out += fmt::format(
        "   <Attribute Name=\"{}\" AttributeType=\"Scalar\" Center=\"Node\">\n"
        "    <DataItem Dimensions=\"{}\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">{}:{}</DataItem>\n"
        "   </Attribute>\n",
        viewer_name(path), dims, h5_name, path);
  out += "  </Grid>\n </Domain>\n</Xdmf>\n";
  return out;
}

}  // namespace bhnsid::io_hdf5
