#include "core/contact/geometry/assignment.hpp"

#include <cmath>
#include <optional>
#include <vector>

#include "core/contact/geometry/patch_projection.hpp"

namespace stoss::contact {

bool accepts(const Projection& p, double eps, double g_max) {
  return p.converged && inside(p.xi, eps) && p.gap > -g_max;  // §3.4
}

bool better(const FaceProjection& a, const FaceProjection& b, double size) {
  const double ga = std::abs(a.projection.gap), gb = std::abs(b.projection.gap);
  if (std::abs(ga - gb) > NarrowPhase::gap_tie * size) return ga < gb;
  const double xa = a.projection.xi.cwiseAbs().maxCoeff(), xb = b.projection.xi.cwiseAbs().maxCoeff();
  if (std::abs(xa - xb) > NarrowPhase::xi_tie) return xa < xb;
  return a.face < b.face;
}

FaceProjection project_on(const Eigen::Vector3d& slave, int face, const PairSurfaces& s,
                          const Eigen::VectorXd& x, const Eigen::Vector2d& xi_start) {
  FaceProjection out;
  out.face = face;
  out.projection = s.smooth() ? patch_projection(slave, s.patches[face], x, xi_start)
                              : closest_point_projection(slave, face_positions(s.faces[face], x), xi_start);
  return out;
}

FaceProjection best_face(const Eigen::Vector3d& slave, std::span<const int> faces, const PairSurfaces& s,
                         const Eigen::VectorXd& x, int skip) {
  std::vector<FaceProjection> trials;
  trials.reserve(faces.size());
  for (int f : faces)
    if (f != skip) trials.push_back(project_on(slave, f, s, x));
  for (const double eps : {NarrowPhase::eps_xi, NarrowPhase::eps_ext}) {
    std::optional<FaceProjection> best;
    for (const FaceProjection& t : trials) {
      const double size = s.face_size[t.face];
      if (!accepts(t.projection, eps, NarrowPhase::max_depth_ratio * size)) continue;
      if (!best || better(t, *best, size)) best = t;
    }
    if (best) {
      best->extended = eps == NarrowPhase::eps_ext;
      return *best;
    }
  }
  return {};
}

}  // namespace stoss::contact
