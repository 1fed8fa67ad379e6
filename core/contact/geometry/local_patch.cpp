#include "core/contact/geometry/local_patch.hpp"

#include <numeric>

namespace stoss::contact {

TensorPatch local_patch(const TensorPatch& p) {
  TensorPatch local = p;
  std::iota(local.nodes.begin(), local.nodes.end(), 1);
  return local;
}

Eigen::VectorXd local_positions(int slave, const TensorPatch& p, const Eigen::VectorXd& x) {
  Eigen::VectorXd out(3 + 3 * p.size());
  out.head<3>() = x.segment<3>(3 * slave);
  for (int K = 0; K < p.size(); ++K) out.segment<3>(3 + 3 * K) = x.segment<3>(3 * p.nodes[K]);
  return out;
}

}  // namespace stoss::contact
