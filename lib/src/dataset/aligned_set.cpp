#include "mocapdb/dataset/aligned_set.hpp"

#include "mocapdb/core/error.hpp"

namespace mocapdb {

MatX AlignedSet::inverse_warp_increments() const {
    if (warps.rows() < 2) return MatX(0, warps.cols());
    return warps.bottomRows(warps.rows() - 1) - warps.topRows(warps.rows() - 1);
}

void validate(const AlignedSet& a) {
    const Eigen::Index d = a.dofs(), t = a.frames(), n = a.samples();
    auto fail = [](const std::string& what) { throw InvalidArgument("aligned set: " + what); };
    if (a.method != "dtw" && a.method != "linear") fail("method must be 'dtw' or 'linear', found '" + a.method + "'");
    if (d < 6 || t < 2 || n < 1) fail("tensor must be at least 6 dofs by 2 frames by 1 sample");
    if (a.warps.rows() != t || a.warps.cols() != n)
        fail("warps are " + std::to_string(a.warps.rows()) + " by " + std::to_string(a.warps.cols()) +
             ", expected frames by samples = " + std::to_string(t) + " by " + std::to_string(n));
    if (a.mean.size() != d || a.scale.size() != d) fail("mean and scale must have one value per dof");
    if (a.canonical.size() != static_cast<std::size_t>(n)) fail("one canonicalization per sample is required");
    if (a.reference >= static_cast<std::size_t>(n)) fail("reference sample index out of range");
    if (!a.warps.allFinite() || !a.mean.allFinite() || !a.scale.allFinite()) fail("non-finite warp, mean or scale");
    if ((a.scale.array() <= 0.0).any()) fail("scales must be positive");
    if ((a.inverse_warp_increments().array() <= 0.0).any()) fail("warps must be strictly increasing");
    const Eigen::Tensor<bool, 0> finite = a.tensor.isfinite().all();
    if (!finite()) fail("non-finite tensor value");
}

}  // namespace mocapdb
