#include "mocapdb/tensor/tucker.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "hosvd_internal.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/mode_product.hpp"
#include "mocapdb/tensor/sample_decoder.hpp"

namespace mocapdb::tensor {

using detail::idx;

namespace {

void check_lod(const Ranks& ranks, const Ranks& lod, const char* where) {
    for (int n = 0; n < 3; ++n) {
        if (lod[n] < 1 || lod[n] > ranks[n]) {
            throw InvalidArgument(std::string(where) + ": level of detail lod[" + std::to_string(n) + "] (" +
                                  mode_name(n) + ") must be in [1, " + idx(ranks[n]) + "], got " + idx(lod[n]));
        }
    }
}

// The leading r1 by r2 by r3 block of the core.
Tensor3 core_block(const Tensor3& core, const Ranks& lod) {
    if (lod[0] == core.dimension(0) && lod[1] == core.dimension(1) && lod[2] == core.dimension(2)) return core;
    Tensor3 out(lod[0], lod[1], lod[2]);
    for (Eigen::Index k = 0; k < lod[2]; ++k) {
        for (Eigen::Index j = 0; j < lod[1]; ++j) {
            for (Eigen::Index i = 0; i < lod[0]; ++i) out(i, j, k) = core(i, j, k);
        }
    }
    return out;
}

// r1-vector: core_lod x_1 u_time x_2 u_sample (first entries of the rows).
VecX contract_core(const Tensor3& core, const Ranks& lod, const Eigen::Ref<const Eigen::RowVectorXd>& u_time,
                   const Eigen::Ref<const Eigen::RowVectorXd>& u_sample) {
    const Eigen::Index r0 = core.dimension(0), r1 = core.dimension(1);
    VecX g = VecX::Zero(lod[0]);
    for (Eigen::Index k = 0; k < lod[2]; ++k) {
        const double s = u_sample(k);
        if (s == 0.0) continue;
        const Eigen::Map<const MatX> slice(core.data() + k * r0 * r1, r0, r1);
        g.noalias() += s * (slice.topLeftCorner(lod[0], lod[1]) * u_time.head(lod[1]).transpose());
    }
    return g;
}

}  // namespace

const char* to_string(TuckerMethod method) {
    switch (method) {
        case TuckerMethod::Hosvd: return "hosvd";
        case TuckerMethod::StHosvd: return "st-hosvd";
        case TuckerMethod::Hooi: return "hooi";
    }
    return "unknown";
}

const char* to_string(TuckerStatus status) {
    switch (status) {
        case TuckerStatus::Ok: return "ok";
        case TuckerStatus::Converged: return "converged";
        case TuckerStatus::MaxIterations: return "max-iterations";
        case TuckerStatus::Stalled: return "stalled";
    }
    return "unknown";
}

double hosvd_error_bound(const ModeSpectra& spectra, const Ranks& ranks) {
    double sum = 0.0;
    for (int n = 0; n < 3; ++n) {
        const VecX& s = spectra.squared_sv[static_cast<std::size_t>(n)];
        if (ranks[n] < 0 || ranks[n] > s.size()) {
            throw InvalidArgument("hosvd_error_bound: ranks[" + std::to_string(n) + "] (" + mode_name(n) +
                                  ") must be in [0, " + idx(s.size()) + "], got " + idx(ranks[n]));
        }
        sum += s.tail(s.size() - ranks[n]).sum();
    }
    return std::sqrt(sum);
}

Eigen::Index tucker_parameter_count(const Dims3& dims, const Ranks& ranks) {
    return ranks[0] * ranks[1] * ranks[2] + dims[0] * ranks[0] + dims[1] * ranks[1] + dims[2] * ranks[2];
}

double tucker_compression_ratio(const Dims3& dims, const Ranks& ranks) {
    const Eigen::Index p = tucker_parameter_count(dims, ranks);
    if (p <= 0) return 0.0;
    return static_cast<double>(dims[0] * dims[1] * dims[2]) / static_cast<double>(p);
}

void check_ranks(const Dims3& dims, const Ranks& ranks, const char* where) {
    for (int n = 0; n < 3; ++n) {
        if (dims[n] < 1) {
            throw InvalidArgument(std::string(where) + ": the tensor is empty (dimension " + std::to_string(n) + " (" +
                                  mode_name(n) + ") is " + idx(dims[n]) + ")");
        }
    }
    for (int n = 0; n < 3; ++n) {
        if (ranks[n] < 1 || ranks[n] > dims[n]) {
            throw InvalidArgument(std::string(where) + ": ranks[" + std::to_string(n) + "] (" + mode_name(n) +
                                  ") must be in [1, " + idx(dims[n]) + "], got " + idx(ranks[n]));
        }
    }
}

void check_tensor(const Tensor3& a, const char* where) {
    for (int n = 0; n < 3; ++n) {
        if (a.dimension(n) < 1) {
            throw InvalidArgument(std::string(where) + ": the tensor must not be empty, got " + idx(a.dimension(0)) +
                                  " by " + idx(a.dimension(1)) + " by " + idx(a.dimension(2)));
        }
    }
    if (!Eigen::Map<const VecX>(a.data(), a.size()).allFinite()) {
        throw InvalidArgument(std::string(where) + ": every element of the tensor must be finite");
    }
}

Tensor3 TuckerModel::reconstruct() const { return reconstruct(ranks); }

Tensor3 TuckerModel::reconstruct(const Ranks& lod) const {
    check_lod(ranks, lod, "TuckerModel::reconstruct");
    return SampleDecoder(core, lod, U[0], U[1], U[2]).decode_all();
}

MatX TuckerModel::reconstruct_sample(Eigen::Index n) const {
    if (n < 0 || n >= U[2].rows()) {
        throw InvalidArgument("TuckerModel::reconstruct_sample: sample index must be in [0, " + idx(U[2].rows()) +
                              "), got " + idx(n));
    }
    // (G x_2 u_sample) is R1 by R2; the sample is U_dof (G x_2 u) U_time^T.
    const Eigen::Map<const MatX> g3(core.data(), ranks[0] * ranks[1], ranks[2]);
    VecX m = VecX::Zero(ranks[0] * ranks[1]);
    m.noalias() += g3 * U[2].row(n).transpose();
    const Eigen::Map<const MatX> gm(m.data(), ranks[0], ranks[1]);
    MatX left(U[0].rows(), ranks[1]);
    left.noalias() = U[0] * gm;
    MatX out(U[0].rows(), U[1].rows());
    out.noalias() = left * U[1].transpose();
    return out;
}

VecX TuckerModel::pose(Eigen::Index t, Eigen::Index n) const {
    if (t < 0 || t >= U[1].rows()) {
        throw InvalidArgument("TuckerModel::pose: time index must be in [0, " + idx(U[1].rows()) + "), got " + idx(t));
    }
    if (n < 0 || n >= U[2].rows()) {
        throw InvalidArgument("TuckerModel::pose: sample index must be in [0, " + idx(U[2].rows()) + "), got " +
                              idx(n));
    }
    const Eigen::RowVectorXd ut = U[1].row(t);
    const Eigen::RowVectorXd us = U[2].row(n);
    return pose(ut, us, ranks);
}

VecX TuckerModel::pose(const Eigen::Ref<const Eigen::RowVectorXd>& u_time,
                       const Eigen::Ref<const Eigen::RowVectorXd>& u_sample) const {
    return pose(u_time, u_sample, ranks);
}

VecX TuckerModel::pose(const Eigen::Ref<const Eigen::RowVectorXd>& u_time,
                       const Eigen::Ref<const Eigen::RowVectorXd>& u_sample, const Ranks& lod) const {
    check_lod(ranks, lod, "TuckerModel::pose");
    if (u_time.size() != ranks[1] || u_sample.size() != ranks[2]) {
        throw InvalidArgument("TuckerModel::pose: u_time must have R2 = " + idx(ranks[1]) +
                              " entries and u_sample R3 = " + idx(ranks[2]) + ", got " + idx(u_time.size()) + " and " +
                              idx(u_sample.size()));
    }
    const VecX g = contract_core(core, lod, u_time, u_sample);
    VecX q(U[0].rows());
    q.noalias() = U[0].leftCols(lod[0]) * g;
    return q;
}

Eigen::Index TuckerModel::parameter_count() const { return tucker_parameter_count(dims(), ranks); }

double TuckerModel::compression_ratio() const { return tucker_compression_ratio(dims(), ranks); }

TuckerModel truncate(const TuckerModel& model, const Ranks& lod) {
    check_lod(model.ranks, lod, "truncate");
    TuckerModel out = model;
    out.core = core_block(model.core, lod);
    for (std::size_t n = 0; n < 3; ++n) out.U[n] = model.U[n].leftCols(lod[n]);
    out.ranks = lod;
    return out;
}

double absolute_error(const Tensor3& a, const TuckerModel& model) {
    const Dims3 d = model.dims();
    if (a.dimension(0) != d[0] || a.dimension(1) != d[1] || a.dimension(2) != d[2]) {
        throw InvalidArgument("absolute_error: the tensor must be " + idx(d[0]) + " by " + idx(d[1]) + " by " +
                              idx(d[2]) + " like the model, got " + idx(a.dimension(0)) + " by " + idx(a.dimension(1)) +
                              " by " + idx(a.dimension(2)));
    }
    const Tensor3 r = model.reconstruct();
    if (a.size() == 0) return 0.0;
    return (Eigen::Map<const VecX>(a.data(), a.size()) - Eigen::Map<const VecX>(r.data(), r.size())).norm();
}

double relative_error(const Tensor3& a, const TuckerModel& model) {
    const double err = absolute_error(a, model);
    const double norm = std::sqrt(squared_norm(a));
    if (norm == 0.0) return err == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
    return err / norm;
}

// ---------------------------------------------------------------------------------------------------
PoseEvaluator::PoseEvaluator(const TuckerModel& model, Order order) : PoseEvaluator(model, model.ranks, order) {}

PoseEvaluator::PoseEvaluator(const TuckerModel& model, const Ranks& lod, Order order) {
    check_lod(model.ranks, lod, "PoseEvaluator");
    dofs_ = model.U[0].rows();
    lod_ = lod;
    const Eigen::Index r1 = lod[0], r2 = lod[1], r3 = lod[2];
    if (order == Order::Auto) {
        const Eigen::Index precomputed = dofs_ * r2 * r3 + r2 * r3;
        const Eigen::Index core_first = r1 * r2 * r3 + r1 * r2 + dofs_ * r1;
        order = precomputed < core_first ? Order::DofPrecomputed : Order::CoreFirst;
    }
    order_ = order;
    // The full ranks use the core as it is (no copy of the block: a model's core can be tens of MB).
    const bool full =
        lod[0] == model.core.dimension(0) && lod[1] == model.core.dimension(1) && lod[2] == model.core.dimension(2);
    const Tensor3 block = full ? Tensor3() : core_block(model.core, lod);
    const double* core = full ? model.core.data() : block.data();
    if (order_ == Order::DofPrecomputed) {
        w_.resize(dofs_, r2 * r3);
        w_.noalias() = model.U[0].leftCols(r1) * Eigen::Map<const MatX>(core, r1, r2 * r3);
    } else {
        core_ = Eigen::Map<const MatX>(core, r1 * r2, r3);
        u_dof_ = model.U[0].leftCols(r1);
    }
}

void PoseEvaluator::evaluate(const Eigen::Ref<const Eigen::RowVectorXd>& u_time,
                             const Eigen::Ref<const Eigen::RowVectorXd>& u_sample, Eigen::Ref<VecX> out_pose,
                             Workspace& ws) const {
    const Eigen::Index r1 = lod_[0], r2 = lod_[1], r3 = lod_[2];
    if (u_time.size() < r2 || u_sample.size() < r3 || out_pose.size() != dofs_) {
        throw InvalidArgument("PoseEvaluator::evaluate: u_time needs >= " + idx(r2) +
                              " entries, u_sample >= " + idx(r3) + ", out_pose exactly " + idx(dofs_) + "; got " +
                              idx(u_time.size()) + ", " + idx(u_sample.size()) + ", " + idx(out_pose.size()));
    }
    if (order_ == Order::DofPrecomputed) {
        if (ws.buffer.size() < r2 * r3) ws.buffer.resize(r2 * r3);
        double* v = ws.buffer.data();
        for (Eigen::Index k = 0; k < r3; ++k) {
            const double s = u_sample(k);
            for (Eigen::Index j = 0; j < r2; ++j) v[j + r2 * k] = s * u_time(j);
        }
        out_pose.noalias() = w_ * Eigen::Map<const VecX>(v, r2 * r3);
    } else {
        if (ws.buffer.size() < r1 * r2 + r1) ws.buffer.resize(r1 * r2 + r1);
        Eigen::Map<VecX> m(ws.buffer.data(), r1 * r2);
        Eigen::Map<VecX> g(ws.buffer.data() + r1 * r2, r1);
        m.noalias() = core_ * u_sample.head(r3).transpose();
        g.noalias() = Eigen::Map<const MatX>(m.data(), r1, r2) * u_time.head(r2).transpose();
        out_pose.noalias() = u_dof_ * g;
    }
}

VecX PoseEvaluator::evaluate(const Eigen::Ref<const Eigen::RowVectorXd>& u_time,
                             const Eigen::Ref<const Eigen::RowVectorXd>& u_sample) const {
    Workspace ws;
    VecX q(dofs_);
    evaluate(u_time, u_sample, q, ws);
    return q;
}

}  // namespace mocapdb::tensor
