#pragma once
// Dense state layout shared by every concern: one row per node, columns x, y, z.
// Column-major so that a state block is directly a CHOLMOD dense right-hand side (n x 3).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace weft {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using NodeMatrix = Eigen::Matrix<double, Eigen::Dynamic, 3>;  // m x 3 positions/velocities/forces
using TriangleIndices = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

}  // namespace weft
