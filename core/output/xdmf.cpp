#include "core/output/xdmf.hpp"

#include <sstream>

#include "core/output/layout.hpp"
#include "core/output/number_text.hpp"

namespace stoss::output {

namespace {

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string dims(long a) {
  return std::to_string(a);
}
std::string dims(long a, long b) {
  return std::to_string(a) + " " + std::to_string(b);
}

/// A DataItem for a whole HDF5 dataset.
std::string hdf_item(const XdmfLayout& l, const std::string& dataset, const std::string& dimensions,
                     const std::string& number_type, int precision) {
  return "<DataItem Dimensions=\"" + dimensions + "\" NumberType=\"" + number_type + "\" Precision=\"" +
         std::to_string(precision) + "\" Format=\"HDF\">" + escaped(l.h5_file) + ":" + dataset +
         "</DataItem>";
}

std::string attribute(const std::string& name, const std::string& type, const std::string& center,
                      const std::string& item) {
  return "        <Attribute Name=\"" + name + "\" AttributeType=\"" + type + "\" Center=\"" + center +
         "\">\n          " + item + "\n        </Attribute>\n";
}

std::string topology(const XdmfLayout& l) {
  return "        <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"" +
         std::to_string(l.element_count) + "\" NodesPerElement=\"8\">\n          " +
         hdf_item(l, "/mesh/hex8", dims(l.element_count, 8), "Int", 8) + "\n        </Topology>\n";
}

std::string geometry(const XdmfLayout& l, const std::string& dataset) {
  return "        <Geometry GeometryType=\"XYZ\">\n          " +
         hdf_item(l, dataset, dims(l.node_count, 3), "Float", 8) + "\n        </Geometry>\n";
}

std::string frame_grid(const XdmfLayout& l, long k) {
  const long N = l.node_count, E = l.element_count;
  const auto field = [&](const char* name) { return frame_dataset(k, name); };
  std::ostringstream out;
  out << "      <Grid Name=\"frame_" << k << "\" GridType=\"Uniform\">\n"
      << "        <Time Value=\"" << shortest_text(l.frame_times[k]) << "\"/>\n"
      << topology(l) << geometry(l, field("position"))
      << attribute("displacement", "Vector", "Node",
                   hdf_item(l, field("displacement"), dims(N, 3), "Float", 8))
      << attribute("velocity", "Vector", "Node", hdf_item(l, field("velocity"), dims(N, 3), "Float", 8));
  if (l.contact_pressure)
    out << attribute("contact_pressure", "Scalar", "Node",
                     hdf_item(l, field("contact_pressure"), dims(N), "Float", 8));
  if (l.stress)
    out << attribute("von_mises", "Scalar", "Cell", hdf_item(l, field("von_mises"), dims(E), "Float", 8))
        << attribute("cauchy_stress", "Tensor6", "Cell",
                     hdf_item(l, field("cauchy_stress"), dims(E, 6), "Float", 8));
  out << attribute("reference_position", "Vector", "Node", hdf_item(l, "/mesh/nodes", dims(N, 3), "Float", 8))
      << attribute("body", "Scalar", "Cell", hdf_item(l, "/mesh/body", dims(E), "Int", 4))
      << "      </Grid>\n";
  return out.str();
}

const char* const header =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<Xdmf Version=\"3.0\">\n"
    "  <Domain>\n";

}  // namespace

std::string xdmf_document(const XdmfLayout& layout) {
  std::ostringstream out;
  out << header << "    <Grid Name=\"frames\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (long k = 0; k < static_cast<long>(layout.frame_times.size()); ++k) out << frame_grid(layout, k);
  out << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return out.str();
}

std::string xdmf_mesh_document(const XdmfLayout& l) {
  std::ostringstream out;
  out << header << "    <Grid Name=\"mesh\" GridType=\"Uniform\">\n"
      << topology(l) << geometry(l, "/mesh/nodes")
      << attribute("body", "Scalar", "Cell", hdf_item(l, "/mesh/body", dims(l.element_count), "Int", 4))
      << attribute("node_body", "Scalar", "Node",
                   hdf_item(l, "/mesh/node_body", dims(l.node_count), "Int", 4))
      << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return out.str();
}

}  // namespace stoss::output
