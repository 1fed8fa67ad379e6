#include "core/contact/contact_term.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "core/contact/geometry/assignment.hpp"
#include "core/contact/geometry/smooth_surface.hpp"

namespace stoss::contact {

ContactTerm::ContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair)
    : pair_(pair), surfaces_(pair_surfaces(mesh, pair.slave, pair.master)) {
  if (pair.master_surface != model::MasterSurface::smooth) return;
  SmoothSurface smooth = smooth_surface(surfaces_.faces);
  if (!smooth.ok()) throw std::invalid_argument("contact master " + pair.master + ": " + smooth.problem);
  surfaces_.patches = std::move(smooth.patches);
}

void ContactTerm::contact_pressure(Eigen::VectorXd& p) const {
  for (const auto& [node, value] : pressure_) p[node] = value;
}

void ContactTerm::log(const time::StepContext& step, const std::string& line) const {
  if (step.log && *step.log) (*step.log)(name() + ": " + line);
}

void ContactTerm::measure_closest_penetration(const time::StepContext& step, const Eigen::VectorXd& x) {
  for (int i : broad_.near_slaves()) {
    const Eigen::Vector3d x_s = x.segment<3>(3 * surfaces_.slave_nodes[i]);
    const FaceProjection best = best_face(x_s, broad_.candidates(i), surfaces_, x);
    if (best.found()) {
      report_.max_penetration = std::max(report_.max_penetration, -best.projection.gap);
      continue;
    }
    for (int f : broad_.candidates(i)) {  // level with the surface, yet no face accepts it
      const Projection p = project_on(x_s, f, surfaces_, x).projection;
      if (p.converged && std::abs(p.gap) < NarrowPhase::max_depth_ratio * surfaces_.face_size[f]) {
        ++report_.unassigned;
        break;
      }
    }
  }
  if (surfaces_.smooth()) measure_faceted_penetration(x);
  if (report_.unassigned > 0)
    log(step, std::to_string(report_.unassigned) +
                  " slave node(s) level with the master surface project onto no face (NTS blind spot, §3.4): "
                  "no contact element for them; refine the master mesh");
}

void ContactTerm::measure_faceted_penetration(const Eigen::VectorXd& x) {
  for (int i : broad_.near_slaves()) {
    const Eigen::Vector3d x_s = x.segment<3>(3 * surfaces_.slave_nodes[i]);
    double closest = std::numeric_limits<double>::infinity(), gap = 0;
    for (int f : broad_.candidates(i)) {
      const Projection p = closest_point_projection(x_s, face_positions(surfaces_.faces[f], x));
      if (!accepts(p, NarrowPhase::eps_ext, NarrowPhase::max_depth_ratio * surfaces_.face_size[f])) continue;
      if (std::abs(p.gap) < closest) closest = std::abs(p.gap), gap = p.gap;
    }
    report_.max_faceted_penetration = std::max(report_.max_faceted_penetration, -gap);
  }
}

std::string ContactTerm::scientific(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3e", v);
  return buffer;
}

}  // namespace stoss::contact
