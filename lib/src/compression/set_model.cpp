#include "mocapdb/compression/set_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

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
    // In place: one D x T x N tensor at a time (sets of 10 000 windows).
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
    : decoder_(core, ranks, dof_basis, time_basis, sample_basis), mean_(&mean), weight_(&weight) {
    if (mean.size() != dof_basis.rows() || weight.size() != dof_basis.rows())
        throw InvalidArgument("SampleReconstruction: " + std::to_string(dof_basis.rows()) + " dofs, mean of " +
                              std::to_string(mean.size()) + " and weight of " + std::to_string(weight.size()));
}

void SampleReconstruction::operator()(const std::vector<Eigen::Index>& samples, MatX& out) const {
    decoder_.decode(samples, out);
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
    if (m.weight.size() != d)
        fail("weight has " + std::to_string(m.weight.size()) + " entries, mean " + std::to_string(d));
    if (!(m.weight.array() > 0.0).all() || !m.weight.allFinite()) fail("weights must be finite and > 0");
    if (!m.mean.allFinite()) fail("mean is not finite");
    if (t.U[0].rows() != d)
        fail("dof basis has " + std::to_string(t.U[0].rows()) + " rows, expected " + std::to_string(d));
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
