#pragma once
/// @file Names of the result file layout (format stoss-result/2), shared by the writer, the reader and
/// the XDMF sidecars.
///
///   /                         attributes format = "stoss-result/2", stoss_version, scheme, step, end,
///                             effects, scene, complete, wall_seconds
///   /mesh/nodes               [N,3] float64  reference coordinates
///   /mesh/hex8                [E,8] int64    node indices, VTK_HEXAHEDRON order
///   /mesh/body                [E]   int32    body index of each element; attribute names = body names
///   /mesh/node_body           [N]   int32    body index of each node
///   /mesh/surfaces/<b>/<s>    [F,4] int64    quads of surface "<b>/<s>" (outward order); attribute name
///   /series/<name>            [S] or [S,c]   one row per converged step (unchanged from format 1)
///   /frames/time              [K]   float64
///   /frames/<k>/position      [N,3] float64  current coordinates x = X + u
///   /frames/<k>/velocity      [N,3] float64
///   /frames/<k>/displacement  [N,3] float64  u = x − X
///   /frames/<k>/contact_pressure [N] float64 (scenes with contact)
///   /frames/<k>/cauchy_stress [E,6] float64  element average, (xx, xy, xz, yy, yz, zz) (when every body
///                                            has a material)
///   /frames/<k>/von_mises     [E]   float64  of cauchy_stress
///
/// Format 1 stored frames as [K,N,…] datasets /frames/position etc. and is still read by ResultFile.
/// One dataset per frame keeps the XDMF sidecars to plain DataItems: the HyperSlab items of format 1
/// were not read by ParaView's Xdmf3 readers nor by meshio.

#include <string>

namespace stoss::output {

inline constexpr const char* result_format = "stoss-result/2";
inline constexpr const char* result_format_1 = "stoss-result/1";

/// "/frames/<k>/<name>".
inline std::string frame_dataset(long k, const std::string& name) {
  return "/frames/" + std::to_string(k) + "/" + name;
}

}  // namespace stoss::output
