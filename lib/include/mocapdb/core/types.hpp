#pragma once
// Scalar type and Eigen aliases shared by every module.
// Conventions: lengths in centimetres, angles in radians, Y is up, time in seconds.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mocapdb {

using Scalar = double;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;
using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;
/// Row-major dynamic matrix: one row per frame, one column per channel (the layout of BVH/AMC rows).
using FrameMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

constexpr double kPi = 3.14159265358979323846;

}  // namespace mocapdb
