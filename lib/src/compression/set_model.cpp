#include "mocapdb/compression/set_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core_terms.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/hosvd.hpp"

namespace mocapdb::compression {
namespace {

void check_dof_vector(const Tensor3& a, const VecX& v, const char* name) {
    if (v.size() != a.dimension(0))
        throw InvalidArgument(std::string("pose tensor has ") + std::to_string(a.dimension(0)) + " dofs, " + name +
                              " has " + std::to_string(v.size()) + " entries");
}

}  // namespace

VecX dof_means(const Tensor3& poses) {
    const Eigen::Index d = poses.dimension(0);
    const Eigen::Index columns = poses.dimension(1) * poses.dimension(2);
    if (columns == 0) return VecX::Zero(d);
    return Eigen::Map<const MatX>(poses.data(), d, columns).rowwise().mean();
}

void weighted_centred_in_place(Tensor3& poses, const VecX& mean, const VecX& weight) {
    check_dof_vector(poses, mean, "mean");
    check_dof_vector(poses, weight, "weight");
    if (!(weight.array() > 0.0).all()) throw InvalidArgument("weighted_centred: every weight must be > 0");
    const Eigen::Index d = poses.dimension(0), columns = poses.dimension(1) * poses.dimension(2);
    Eigen::Map<MatX> m(poses.data(), d, columns);
    m = (m.colwise() - mean).array().colwise() * weight.array();
}

Tensor3 weighted_centred(const Tensor3& poses, const VecX& mean, const VecX& weight) {
    Tensor3 x = poses;
    weighted_centred_in_place(x, mean, weight);
    return x;
}

Tensor3 from_weighted_centred(const Tensor3& x, const VecX& mean, const VecX& weight) {
    check_dof_vector(x, mean, "mean");
    check_dof_vector(x, weight, "weight");
    Tensor3 a(x.dimensions());
    const Eigen::Index d = x.dimension(0), columns = x.dimension(1) * x.dimension(2);
    Eigen::Map<MatX>(a.data(), d, columns) =
        (Eigen::Map<const MatX>(x.data(), d, columns).array().colwise() / weight.array()).matrix().colwise() + mean;
    return a;
}

Tensor3 SetModel::reconstruct() const {
    // In place: one D x T x N tensor at a time (issue #16: sets of 10 000 windows).
    Tensor3 a = tucker.reconstruct();
    check_dof_vector(a, mean, "mean");
    check_dof_vector(a, weight, "weight");
    const Eigen::Index d = a.dimension(0), columns = a.dimension(1) * a.dimension(2);
    Eigen::Map<MatX> m(a.data(), d, columns);
    m = (m.array().colwise() / weight.array()).matrix().colwise() + mean;
    return a;
}

Tensor3 SetModel::reconstruct(const tensor::Ranks& lod) const {
    return from_weighted_centred(tucker.reconstruct(lod), mean, weight);
}

SampleReconstruction::SampleReconstruction(const SetModel& model)
    : SampleReconstruction(model.tucker.core, tensor::dims_of(model.tucker.core), model.tucker.U[0], model.tucker.U[1],
                           model.tucker.U[2], model.mean, model.weight) {}

SampleReconstruction::SampleReconstruction(const Tensor3& core, const tensor::Ranks& ranks,
                                           const Eigen::Ref<const MatX>& dof_basis,
                                           const Eigen::Ref<const MatX>& time_basis, const MatX& sample_basis,
                                           const VecX& mean, const VecX& weight)
    : sample_basis_(&sample_basis), sample_rank_(ranks[2]), mean_(&mean), weight_(&weight) {
    const Eigen::Index r0 = ranks[0], r1 = ranks[1], f0 = core.dimension(0), f1 = core.dimension(1);
    if (r0 < 0 || r1 < 0 || sample_rank_ < 0 || r0 > f0 || r1 > f1 || sample_rank_ > core.dimension(2) ||
        dof_basis.cols() < r0 || time_basis.cols() < r1 || sample_basis.cols() < sample_rank_ ||
        mean.size() != dof_basis.rows() || weight.size() != dof_basis.rows())
        throw InvalidArgument("SampleReconstruction: bases of " + std::to_string(dof_basis.cols()) + ", " +
                              std::to_string(time_basis.cols()) + ", " + std::to_string(sample_basis.cols()) +
                              " columns and " + std::to_string(dof_basis.rows()) + " dofs (mean " +
                              std::to_string(mean.size()) + ", weight " + std::to_string(weight.size()) +
                              ") for ranks " + std::to_string(r0) + " x " + std::to_string(r1) + " x " +
                              std::to_string(sample_rank_) + " of a core of " + std::to_string(f0) + " x " +
                              std::to_string(f1) + " x " + std::to_string(core.dimension(2)));
    // The first two mode products of TuckerModel::reconstruct(), slice by slice of the sample mode
    // (each output value is the same sum, in the same order, as in its one product over the whole
    // unfolding), the slices on the machine's cores (independent, so the values do not depend on the
    // thread count); the last product (sample mode) is done per call.
    detail::core_terms(core, dof_basis.leftCols(r0), time_basis.leftCols(r1), 0, sample_rank_, dof_time_);
}

void SampleReconstruction::operator()(const std::vector<Eigen::Index>& samples, MatX& out) const {
    const Eigen::Index d = mean_->size(), frames = dof_time_.rows() / std::max<Eigen::Index>(1, d);
    const Eigen::Index n = sample_basis_->rows();
    const auto count = static_cast<Eigen::Index>(samples.size());
    MatX rows(count, sample_rank_);
    for (Eigen::Index i = 0; i < count; ++i) {
        const Eigen::Index s = samples[static_cast<std::size_t>(i)];
        if (s < 0 || s >= n)
            throw InvalidArgument("SampleReconstruction: sample " + std::to_string(s) + " is not in [0, " +
                                  std::to_string(n) + ")");
        rows.row(i) = sample_basis_->row(s).head(sample_rank_);
    }
    out.resize(d, frames * count);
    Eigen::Map<MatX>(out.data(), d * frames, count).noalias() = dof_time_ * rows.transpose();
    out = (out.array().colwise() / weight_->array()).matrix().colwise() + *mean_;
}

SetModel fit_set_model(const Tensor3& poses, const VecX& weight, const tensor::Ranks& ranks,
                       tensor::TuckerMethod method, const tensor::HooiOptions& hooi) {
    tensor::check_tensor(poses, "fit_set_model");
    const VecX mean = dof_means(poses);
    return fit_weighted_set_model(weighted_centred(poses, mean, weight), mean, weight, ranks, method, hooi);
}

SetModel fit_weighted_set_model(const Tensor3& x, const VecX& mean, const VecX& weight, const tensor::Ranks& ranks,
                                tensor::TuckerMethod method, const tensor::HooiOptions& hooi) {
    tensor::check_tensor(x, "fit_set_model");
    check_dof_vector(x, mean, "mean");
    check_dof_vector(x, weight, "weight");
    SetModel m;
    m.mean = mean;
    m.weight = weight;
    switch (method) {
        case tensor::TuckerMethod::Hosvd: m.tucker = tensor::hosvd(x, ranks, hooi.hosvd); break;
        case tensor::TuckerMethod::StHosvd: m.tucker = tensor::st_hosvd(x, ranks); break;
        case tensor::TuckerMethod::Hooi: m.tucker = tensor::hooi(x, ranks, hooi); break;
    }
    return m;
}

void check(const SetModel& m, const char* where) {
    const auto fail = [&](const std::string& what) { throw InvalidArgument(std::string(where) + ": " + what); };
    const tensor::TuckerModel& t = m.tucker;
    const Eigen::Index d = m.mean.size();
    if (d == 0) fail("the model has no dofs");
    if (m.weight.size() != d) fail("weight has " + std::to_string(m.weight.size()) + " entries, mean " + std::to_string(d));
    if (!(m.weight.array() > 0.0).all() || !m.weight.allFinite()) fail("weights must be finite and > 0");
    if (!m.mean.allFinite()) fail("mean is not finite");
    if (t.U[0].rows() != d) fail("dof basis has " + std::to_string(t.U[0].rows()) + " rows, expected " + std::to_string(d));
    for (int n = 0; n < 3; ++n) {
        if (t.U[n].cols() != t.ranks[n] || t.core.dimension(n) != t.ranks[n])
            fail("basis " + std::to_string(n) + " is " + std::to_string(t.U[n].rows()) + " x " +
                 std::to_string(t.U[n].cols()) + " but the core's dimension " + std::to_string(n) + " is " +
                 std::to_string(t.core.dimension(n)) + " and the rank " + std::to_string(t.ranks[n]));
        if (t.ranks[n] < 1 || t.ranks[n] > t.U[n].rows()) fail("rank " + std::to_string(n) + " out of range");
        if (!t.U[n].allFinite()) fail("basis " + std::to_string(n) + " is not finite");
    }
    for (Eigen::Index i = 0; i < t.core.size(); ++i)
        if (!std::isfinite(t.core.data()[i])) fail("core is not finite");
}

}  // namespace mocapdb::compression
