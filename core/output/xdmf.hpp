#pragma once
/// @file The XDMF 3 sidecars of a result file: result.xdmf (time series, for ParaView and
/// meshio.xdmf.TimeSeriesReader) and result_mesh.xdmf (the reference mesh as one grid, for meshio.read).

#include <string>
#include <vector>

namespace stoss::output {

/// What the sidecars need to know about the HDF5 result they point into (layout.hpp).
struct XdmfLayout {
  std::string h5_file = "result.h5";  ///< relative to the sidecar
  long node_count = 0;                ///< N
  long element_count = 0;             ///< E
  std::vector<double> frame_times;    ///< one per frame, K in all
  bool contact_pressure = false;      ///< whether frames have contact_pressure
  bool stress = false;                ///< whether frames have cauchy_stress and von_mises
};

/// result.xdmf: a Temporal collection, the only grid of the domain, of one Uniform grid per frame:
/// Geometry = /frames/<k>/position (the deformed shape), Topology = /mesh/hex8 (Hexahedron); node
/// attributes displacement, velocity, contact_pressure, reference_position; cell attributes
/// von_mises, cauchy_stress (Tensor6), body. Every DataItem is a whole HDF5 dataset.
std::string xdmf_document(const XdmfLayout& layout);

/// result_mesh.xdmf: one Uniform grid with the reference mesh (/mesh/nodes, /mesh/hex8), cell
/// attribute body and node attribute node_body. meshio.read reads only single-grid files.
std::string xdmf_mesh_document(const XdmfLayout& layout);

}  // namespace stoss::output
