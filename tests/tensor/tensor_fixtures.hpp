#pragma once
// Synthetic tensors for the tensor-module tests (generated here, no data files).
#include <cmath>
#include <random>

#include <Eigen/QR>

#include "mocapdb/tensor/mode_product.hpp"
#include "mocapdb/tensor/unfold.hpp"

namespace mocapdb::test {

using mocapdb::MatX;
using mocapdb::Tensor3;
using mocapdb::VecX;

inline Tensor3 random_tensor(Eigen::Index d0, Eigen::Index d1, Eigen::Index d2, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> nd(0.0, 1.0);
    Tensor3 a(d0, d1, d2);
    for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = nd(rng);
    return a;
}

inline MatX random_matrix(Eigen::Index rows, Eigen::Index cols, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> nd(0.0, 1.0);
    MatX m(rows, cols);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = nd(rng);
    return m;
}

/// rows by cols with orthonormal columns (cols <= rows).
inline MatX random_orthonormal(Eigen::Index rows, Eigen::Index cols, unsigned seed) {
    const MatX g = random_matrix(rows, cols, seed);
    const Eigen::HouseholderQR<MatX> qr(g);
    return qr.householderQ() * MatX::Identity(rows, cols);
}

/// A tensor of exact multilinear rank `ranks` (random core times random orthonormal bases), plus
/// Gaussian noise of relative Frobenius size `noise` (0 for none).
inline Tensor3 low_rank_tensor(const tensor::Dims3& dims, const tensor::Ranks& ranks, double noise, unsigned seed) {
    Tensor3 a = random_tensor(ranks[0], ranks[1], ranks[2], seed);
    for (int n = 0; n < 3; ++n) {
        a = tensor::mode_product(a, random_orthonormal(dims[static_cast<std::size_t>(n)], ranks[static_cast<std::size_t>(n)], seed + 10u + static_cast<unsigned>(n)), n);
    }
    if (noise > 0.0) {
        const Tensor3 e = random_tensor(dims[0], dims[1], dims[2], seed + 100u);
        const double scale = noise * std::sqrt(tensor::squared_norm(a) / tensor::squared_norm(e));
        for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] += scale * e.data()[i];
    }
    return a;
}

/// ||a - b||_F / ||a||_F (same shapes).
inline double rel_diff(const Tensor3& a, const Tensor3& b) {
    const Eigen::Map<const VecX> x(a.data(), a.size()), y(b.data(), b.size());
    return (x - y).norm() / x.norm();
}

inline double rel_diff(const MatX& a, const MatX& b) { return (a - b).norm() / a.norm(); }

}  // namespace mocapdb::test
