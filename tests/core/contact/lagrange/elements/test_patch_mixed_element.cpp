// The mixed energy–momentum element on a tensor patch (docs/smooth_master_surface.md §3) shall have a
// tangent that matches central differences of its residual, satisfy the directional property of its
// discrete gradient, Δq·R_q/h = λ·(g(π_{n+1}) − g(π_n)), to round-off (so (4.11) holds), and exert
// forces with zero sum and zero moment (both momenta). Cases: a face interior, on an edge, at a corner
// (ξ at ±1), at a surface rim and a surface corner (ghost nodes), and the bilinear face.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/smooth_surface.hpp"
#include "core/contact/lagrange/elements/patch_mixed_element.hpp"
#include "tests/core/contact/smooth_test_utils.hpp"

namespace stoss::contact {
namespace {

using test::Grid;

using Case = test::PatchCase;

class PatchMixedElement : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    const Case& c = GetParam();
    test::PickedPatch picked = test::pick(c);
    grid = std::move(picked.grid);
    patch = std::move(picked.patch);
    const Eigen::Vector2d xi = picked.xi;
    std::mt19937 rng(7 + c.face_i + 5 * c.face_j);
    std::normal_distribution<double> n(0, 1);
    const auto jitter = [&](double s) -> Eigen::Vector3d {
      return Eigen::Vector3d(n(rng), n(rng), n(rng)) * s;
    };
    const PatchFrame on = patch_frame(patch, grid.x, xi);
    at_n.master.resize(patch.size(), 3);
    for (int K = 0; K < patch.size(); ++K)
      at_n.master.row(K) = (grid.x.segment<3>(3 * patch.nodes[K]) + jitter(0.01)).transpose();
    at_n.slave = on.y + 0.02 * on.normal + jitter(0.01);
    at_n.d = on.normal + jitter(0.05);
    const double xi_jitter = c.sphere ? 0.001 : 0.01;  // near the vertex: stay in the face's first rings
    at_n.xi = xi + Eigen::Vector2d(xi_jitter * n(rng), xi_jitter * n(rng));
    at_1 = at_n;  // a large step: every coordinate moves
    for (int K = 0; K < patch.size(); ++K) at_1.master.row(K) += jitter(0.05).transpose();
    at_1.slave += jitter(0.05);
    at_1.d += jitter(0.05);
    at_1.xi += c.sphere ? Eigen::Vector2d(0.002 * n(rng), 0.002 * n(rng))
                        : Eigen::Vector2d(0.07 * n(rng), 0.05 * n(rng));
    for (int k = 0; k < 6; ++k) lambda[k] = n(rng);
  }

  Eigen::VectorXd unknowns(const PatchMixedState& s) const {
    const int M = patch.size();
    Eigen::VectorXd q(3 * M + 14);
    q.head<3>() = s.slave;
    for (int K = 0; K < M; ++K) q.segment<3>(3 + 3 * K) = s.master.row(K).transpose();
    q.segment<3>(3 * M + 3) = s.d;
    q.segment<2>(3 * M + 6) = s.xi;
    q.tail<6>() = lambda;
    return q;
  }

  Eigen::VectorXd residual(const Eigen::VectorXd& q) const {
    const int M = patch.size();
    PatchMixedState s;
    s.slave = q.head<3>();
    s.master.resize(M, 3);
    for (int K = 0; K < M; ++K) s.master.row(K) = q.segment<3>(3 + 3 * K).transpose();
    s.d = q.segment<3>(3 * M + 3);
    s.xi = q.segment<2>(3 * M + 6);
    const PatchMixedResult r = patch_mixed_element(patch, at_n, s, q.tail<6>(), f3, h);
    Eigen::VectorXd R(q.size());
    R << r.Rq, r.Rl;
    return R;
  }

  Grid grid;
  TensorPatch patch;
  PatchMixedState at_n, at_1;
  Vector6 lambda;
  double f3 = 0.003, h = 0.01;
};

TEST_P(PatchMixedElement, TangentMatchesCentralDifferences) {
  const Eigen::VectorXd q = unknowns(at_1);
  const PatchMixedResult r = patch_mixed_element(patch, at_n, at_1, lambda, f3, h);
  Eigen::MatrixXd fd(q.size(), q.size());
  const double eps = 1e-6;
  for (int j = 0; j < q.size(); ++j) {
    Eigen::VectorXd up = q, down = q;
    up[j] += eps, down[j] -= eps;
    fd.col(j) = (residual(up) - residual(down)) / (2 * eps);
  }
  EXPECT_LT((r.K - fd).norm(), 1e-7 * fd.norm()) << (r.K - fd).cwiseAbs().maxCoeff();
}

TEST_P(PatchMixedElement, DiscreteGradientIsExactAlongTheStep) {
  const PatchMixedResult r = patch_mixed_element(patch, at_n, at_1, lambda, f3, h);
  const Eigen::VectorXd dq = (unknowns(at_1) - unknowns(at_n)).head(r.Rq.size());
  const double work = dq.dot(r.Rq) / h, change = lambda.dot(r.Rl - r.g_n);
  EXPECT_NEAR(work, change, 1e-13 * (1 + std::abs(change))) << work - change;
  EXPECT_GT(std::abs(change), 1e-3);  // the step is large: the identity is not trivially 0 = 0
}

TEST_P(PatchMixedElement, ForcesHaveZeroSumAndZeroMoment) {
  const PatchMixedResult r = patch_mixed_element(patch, at_n, at_1, lambda, f3, h);
  const int M = patch.size();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  const auto mid = [&](int c) -> Eigen::Vector3d {
    if (c == 0) return 0.5 * (at_n.slave + at_1.slave);
    if (c <= M) return 0.5 * (at_n.master.row(c - 1) + at_1.master.row(c - 1)).transpose();
    return 0.5 * (at_n.d + at_1.d);
  };
  for (int c = 0; c <= M + 1; ++c) {
    const Eigen::Vector3d f = r.Rq.segment<3>(3 * c);
    if (c <= M) sum += f;
    moment += mid(c).cross(f);
  }
  EXPECT_LT(sum.norm(), 1e-15 * r.Rq.norm() * M + 1e-17);
  EXPECT_LT(moment.norm(), 1e-14 * r.Rq.norm());
}

INSTANTIATE_TEST_SUITE_P(
    Cases, PatchMixedElement,
    ::testing::Values(Case{"interior", 1, 2, {0.2, -0.3}}, Case{"on_edge", 1, 1, {1.0, 0.1}},
                      Case{"at_corner", 2, 1, {-1.0, 1.0}}, Case{"rim", 0, 2, {-0.95, 0.3}},
                      Case{"surface_corner", 3, 3, {0.9, 0.97}}, Case{"bilinear", 1, 1, {0.3, 0.4}, true},
                      Case{"extraordinary_ring_3", -1, -1, {0.2, 0.15}, false, true},
                      Case{"extraordinary_ring_8", -1, -1, {0.006, 0.004}, false, true}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace stoss::contact
