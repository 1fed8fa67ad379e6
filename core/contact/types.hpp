#pragma once
/// @file Fixed-size Eigen types shared by the NTS contact element kernels, and the packing of the
/// 15-entry element vector [x_s; y_1; y_2; y_3; y_4] (docs/theory.md §3.3).

#include <Eigen/Core>

namespace stoss::contact {

using SegmentNodes = Eigen::Matrix<double, 4, 3>;  ///< master nodes y_1 … y_4 as rows
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Vector15 = Eigen::Matrix<double, 15, 1>;
using Vector17 = Eigen::Matrix<double, 17, 1>;
using Vector20 = Eigen::Matrix<double, 20, 1>;
using RowVector15 = Eigen::Matrix<double, 1, 15>;
using Matrix2x15 = Eigen::Matrix<double, 2, 15>;
using Matrix3x15 = Eigen::Matrix<double, 3, 15>;
using Matrix15 = Eigen::Matrix<double, 15, 15>;
using Matrix17 = Eigen::Matrix<double, 17, 17>;
using Matrix20 = Eigen::Matrix<double, 20, 20>;
using Matrix6x17 = Eigen::Matrix<double, 6, 17>;
using Matrix17x20 = Eigen::Matrix<double, 17, 20>;
using Matrix20x6 = Eigen::Matrix<double, 20, 6>;
using Matrix6x20 = Eigen::Matrix<double, 6, 20>;

/// The slave node x_s: entries 0–2 of the element vector.
inline Eigen::Vector3d slave_position(const Vector15& x) {
  return x.head<3>();
}

/// The master nodes y_1 … y_4 (rows): entries 3–14 of the element vector, node K at 3 + 3K.
inline SegmentNodes segment_nodes(const Vector15& x) {
  SegmentNodes nodes;
  for (int K = 0; K < 4; ++K) nodes.row(K) = x.segment<3>(3 + 3 * K).transpose();
  return nodes;
}

/// The element vector [x_s; y_1; y_2; y_3; y_4].
inline Vector15 element_vector(const Eigen::Vector3d& slave, const SegmentNodes& nodes) {
  Vector15 x;
  x.head<3>() = slave;
  for (int K = 0; K < 4; ++K) x.segment<3>(3 + 3 * K) = nodes.row(K).transpose();
  return x;
}

}  // namespace stoss::contact
