// The midpoint (formulation §4.2) and HHT-α ((2.11)) NTS elements on a tensor patch
// (docs/smooth_master_surface.md §3.7) shall have tangents that match central differences of their
// residuals, in a face interior, on an edge, at a rim, near an extraordinary vertex and on the bilinear
// face; and their force shall have zero sum (linear momentum).
#include <gtest/gtest.h>

#include <random>

#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/smooth_surface.hpp"
#include "core/contact/lagrange/elements/patch_nts_element.hpp"
#include "tests/core/contact/smooth_test_utils.hpp"

namespace stoss::contact {
namespace {

using test::Grid;

using Case = test::PatchCase;

class PatchNtsElement : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    const test::PickedPatch picked = test::pick(GetParam());
    const Grid& grid = picked.grid;
    const TensorPatch& patch = picked.patch;
    const Eigen::Vector2d xi = picked.xi;
    const PatchFrame on = patch_frame(patch, grid.x, xi);
    local = local_patch(patch);
    x_n.resize(3 + 3 * patch.size());
    x_n.head<3>() = on.y + 0.01 * on.normal;
    for (int K = 0; K < patch.size(); ++K) x_n.segment<3>(3 + 3 * K) = grid.x.segment<3>(3 * patch.nodes[K]);
    std::mt19937 rng(3);
    std::normal_distribution<double> n(0, 1);
    x_1 = x_n;
    for (Eigen::Index i = 0; i < x_1.size(); ++i) x_1[i] += 0.004 * n(rng);
    x_1.head<3>() -= 0.02 * on.normal;  // the slave moves below the surface
    xi_start = xi;
  }

  Eigen::VectorXd residual(bool hht, const Eigen::VectorXd& x, double lambda) const {
    const PatchNtsResult r = hht ? patch_hht_element(local, x, lambda, f3, h, 1 + alpha, xi_start)
                                 : patch_midpoint_element(local, x_n, x, lambda, f3, h, xi_start);
    Eigen::VectorXd R(x.size() + 1);
    R << r.Rx, r.Rl;
    return R;
  }

  void check_tangent(bool hht) const {
    const PatchNtsResult r = hht ? patch_hht_element(local, x_1, lambda, f3, h, 1 + alpha, xi_start)
                                 : patch_midpoint_element(local, x_n, x_1, lambda, f3, h, xi_start);
    ASSERT_TRUE(r.converged);
    const Eigen::Index n = x_1.size();
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + 1, n + 1), fd(n + 1, n + 1);
    K.topLeftCorner(n, n) = r.Kxx;
    K.topRightCorner(n, 1) = r.Kxl;
    K.bottomLeftCorner(1, n) = r.Klx;
    const double eps = 1e-6;
    for (Eigen::Index j = 0; j <= n; ++j) {
      Eigen::VectorXd up = x_1, down = x_1;
      double l_up = lambda, l_down = lambda;
      if (j < n)
        up[j] += eps, down[j] -= eps;
      else
        l_up += eps, l_down -= eps;
      fd.col(j) = (residual(hht, up, l_up) - residual(hht, down, l_down)) / (2 * eps);
    }
    EXPECT_LT((K - fd).norm(), 1e-6 * fd.norm()) << (K - fd).cwiseAbs().maxCoeff();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (Eigen::Index i = 0; i < n; i += 3) sum += r.Rx.segment<3>(i);
    EXPECT_LT(sum.norm(), 1e-14 * r.Rx.norm());
  }

  TensorPatch local;
  Eigen::VectorXd x_n, x_1;
  Eigen::Vector2d xi_start;
  double lambda = -3.2, f3 = 0.001, h = 0.01, alpha = -0.1;
};

TEST_P(PatchNtsElement, MidpointTangentMatchesCentralDifferences) {
  check_tangent(false);
}
TEST_P(PatchNtsElement, HhtTangentMatchesCentralDifferences) {
  check_tangent(true);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, PatchNtsElement,
    ::testing::Values(Case{"interior", 1, 2, {0.2, -0.3}}, Case{"on_edge", 1, 1, {0.98, 0.1}},
                      Case{"corner", 1, 1, {0.97, -0.99}}, Case{"rim", 0, 2, {-0.9, 0.3}},
                      Case{"bilinear", 1, 1, {0.3, 0.4}, true},
                      Case{"extraordinary", -1, -1, {0.1, 0.06}, false, true}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace stoss::contact
