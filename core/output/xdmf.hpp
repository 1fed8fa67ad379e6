#pragma once
/// @file The XDMF 3 sidecar that lets ParaView open a result file as a temporal collection.

#include <string>
#include <vector>

namespace stoss::output {

/// What the sidecar needs to know about the HDF5 result it points into (service.md §3).
struct XdmfLayout {
  std::string h5_file = "result.h5";  ///< relative to the sidecar
  long node_count = 0;                ///< N
  long element_count = 0;             ///< E
  std::vector<double> frame_times;    ///< one per frame, K in all
  bool contact_pressure = false;      ///< whether /frames/contact_pressure exists
};

/// XDMF 3 document: one Uniform grid per frame in a Temporal collection. Geometry is the
/// frame's slab of /frames/position, topology /mesh/hex8 (Hexahedron); velocity (Vector),
/// contact_pressure (Scalar), reference_position (/mesh/nodes) on nodes and body on cells.
std::string xdmf_document(const XdmfLayout& layout);

}  // namespace stoss::output
