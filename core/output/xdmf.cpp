#include "core/output/xdmf.hpp"

#include <sstream>

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

std::string dims(long a, long b) {
  return std::to_string(a) + " " + std::to_string(b);
}
std::string dims(long a, long b, long c) {
  return dims(a, b) + " " + std::to_string(c);
}

/// An HDF item for a whole dataset.
std::string hdf_item(const XdmfLayout& l, const std::string& dataset, const std::string& dimensions,
                     const std::string& number_type, int precision) {
  return "<DataItem Dimensions=\"" + dimensions + "\" NumberType=\"" + number_type + "\" Precision=\"" +
         std::to_string(precision) + "\" Format=\"HDF\">" + escaped(l.h5_file) + ":" + dataset +
         "</DataItem>";
}

/// Frame k of a per-node frame dataset [K,N,width] (width 0: [K,N]).
std::string frame_slab(const XdmfLayout& l, const std::string& dataset, long k, long width) {
  const long K = static_cast<long>(l.frame_times.size()), N = l.node_count;
  const bool vector = width > 0;
  const std::string selection =
      vector ? dims(k, 0, 0) + "  1 1 1  " + dims(1, N, width) : dims(k, 0) + "  1 1  " + dims(1, N);
  return "<DataItem ItemType=\"HyperSlab\" Dimensions=\"" + (vector ? dims(1, N, width) : dims(1, N)) +
         "\" Type=\"HyperSlab\">\n            <DataItem Dimensions=\"3 " + (vector ? "3" : "2") +
         "\" Format=\"XML\">" + selection + "</DataItem>\n            " +
         hdf_item(l, dataset, vector ? dims(K, N, width) : dims(K, N), "Float", 8) +
         "\n          </DataItem>";
}

std::string attribute(const std::string& name, const std::string& type, const std::string& center,
                      const std::string& item) {
  return "        <Attribute Name=\"" + name + "\" AttributeType=\"" + type + "\" Center=\"" + center +
         "\">\n          " + item + "\n        </Attribute>\n";
}

std::string frame_grid(const XdmfLayout& l, long k) {
  const long N = l.node_count, E = l.element_count;
  std::ostringstream out;
  out << "      <Grid Name=\"frame_" << k << "\" GridType=\"Uniform\">\n"
      << "        <Time Value=\"" << shortest_text(l.frame_times[k]) << "\"/>\n"
      << "        <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"" << E
      << "\" NodesPerElement=\"8\">\n"
      << "          " << hdf_item(l, "/mesh/hex8", dims(E, 8), "Int", 8) << "\n        </Topology>\n"
      << "        <Geometry GeometryType=\"XYZ\">\n          " << frame_slab(l, "/frames/position", k, 3)
      << "\n        </Geometry>\n"
      << attribute("velocity", "Vector", "Node", frame_slab(l, "/frames/velocity", k, 3));
  if (l.contact_pressure)
    out << attribute("contact_pressure", "Scalar", "Node", frame_slab(l, "/frames/contact_pressure", k, 0));
  out << attribute("reference_position", "Vector", "Node", hdf_item(l, "/mesh/nodes", dims(N, 3), "Float", 8))
      << attribute("body", "Scalar", "Cell", hdf_item(l, "/mesh/body", std::to_string(E), "Int", 4))
      << "      </Grid>\n";
  return out.str();
}

}  // namespace

std::string xdmf_document(const XdmfLayout& layout) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      << "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
      << "  <Domain>\n"
      << "    <Grid Name=\"frames\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (long k = 0; k < static_cast<long>(layout.frame_times.size()); ++k) out << frame_grid(layout, k);
  out << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return out.str();
}

}  // namespace stoss::output
