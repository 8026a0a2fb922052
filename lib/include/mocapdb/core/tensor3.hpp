#pragma once
// The third-order tensor type of aligned motion sets, shared by the tensor, codec, dataset and store modules.
#include <unsupported/Eigen/CXX11/Tensor>

namespace mocapdb {

using Tensor3 = Eigen::Tensor<double, 3>;  // column-major; for a motion set (dof, time, sample)

}  // namespace mocapdb
