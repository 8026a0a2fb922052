#include "mocapdb/core/float32.hpp"
#include "mocapdb/compression/codecs/pca_baseline.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "mocapdb/core/error.hpp"

namespace mocapdb::compression::codecs {

SamplePca::SamplePca(const Tensor3& a) : dofs_(a.dimension(0)), frames_(a.dimension(1)), samples_(a.dimension(2)) {
    if (a.size() == 0) throw InvalidArgument("SamplePca: empty tensor");
    const Eigen::Index L = dofs_ * frames_, N = samples_;
    const Eigen::Map<const MatX> x(a.data(), L, N);  // column n = sample n flattened
    if (!x.allFinite()) throw InvalidArgument("SamplePca: the tensor has a non-finite element");
    mean_ = x.rowwise().mean();
    const MatX x0 = x.colwise() - mean_;
    const Eigen::Index m = std::min(N, L);
    MatX dirs;  // L by m, columns by decreasing eigenvalue (not yet normalized when N < L)
    VecX eig;
    if (N < L) {
        MatX gram(N, N);
        gram.setZero();
        gram.selfadjointView<Eigen::Lower>().rankUpdate(x0.transpose());
        Eigen::SelfAdjointEigenSolver<MatX> es(gram.selfadjointView<Eigen::Lower>());
        const MatX v = es.eigenvectors().rowwise().reverse();
        eig = es.eigenvalues().reverse();
        dirs.noalias() = x0 * v;  // column j has norm sqrt(eig_j)
    } else {
        MatX cov(L, L);
        cov.setZero();
        cov.selfadjointView<Eigen::Lower>().rankUpdate(x0);
        Eigen::SelfAdjointEigenSolver<MatX> es(cov.selfadjointView<Eigen::Lower>());
        dirs = es.eigenvectors().rowwise().reverse();
        eig = es.eigenvalues().reverse();
    }
    // Orthonormalize keeping the nested spans (the QR of a matrix with orthogonal columns only
    // normalizes them, and cleans up the rounding of the small ones).
    Eigen::HouseholderQR<MatX> qr(dirs);
    basis_ = qr.householderQ() * MatX::Identity(L, m);
    // Sign: each column's largest-magnitude entry positive (deterministic across platforms' QR).
    for (Eigen::Index j = 0; j < m; ++j) {
        Eigen::Index imax = 0;
        basis_.col(j).cwiseAbs().maxCoeff(&imax);
        if (basis_(imax, j) < 0) basis_.col(j) *= -1.0;
    }
    coeffs_.noalias() = basis_.transpose() * x0;
    singular_values_ = eig.head(m).cwiseMax(0.0).cwiseSqrt();
}

void SamplePca::check_k(Eigen::Index k, const char* where) const {
    if (k < 0 || k > max_components())
        throw InvalidArgument(std::string("SamplePca::") + where + ": k = " + std::to_string(k) + " not in 0.." +
                              std::to_string(max_components()));
}

double SamplePca::discarded_energy(Eigen::Index k) const {
    check_k(k, "discarded_energy");
    return singular_values_.tail(max_components() - k).squaredNorm();
}

std::size_t SamplePca::stored_bytes(Eigen::Index k) const {
    check_k(k, "stored_bytes");
    const auto L = static_cast<std::size_t>(dofs_ * frames_);
    const auto uk = static_cast<std::size_t>(k), n = static_cast<std::size_t>(samples_);
    return 4 * (L + uk * L + n * uk);
}

Tensor3 SamplePca::reconstruct(Eigen::Index k, bool float32_storage) const {
    check_k(k, "reconstruct");
    const Eigen::Index L = dofs_ * frames_;
    Tensor3 out(dofs_, frames_, samples_);
    Eigen::Map<MatX> y(out.data(), L, samples_);
    if (float32_storage) {
        MatX mean = mean_, b = basis_.leftCols(k), c = coeffs_.topRows(k);
        round_entries_to_float32(mean);
        round_entries_to_float32(b);
        round_entries_to_float32(c);
        y.noalias() = b * c;
        y.colwise() += mean.col(0);
    } else {
        y.noalias() = basis_.leftCols(k) * coeffs_.topRows(k);
        y.colwise() += mean_;
    }
    return out;
}

}  // namespace mocapdb::compression::codecs
