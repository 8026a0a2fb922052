#pragma once
// Deterministic random control points for the kriging tests.
#include <random>

#include <Eigen/Core>

namespace mocapdb::kriging::test {

/// n points in P = p dimensions, coordinates uniform in [lo, hi), from a fixed seed.
inline Eigen::MatrixXd uniform(Eigen::Index n, Eigen::Index p, unsigned seed, double lo, double hi) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> ud(lo, hi);
    Eigen::MatrixXd m(n, p);
    for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = ud(rng);
    return m;
}

}  // namespace mocapdb::kriging::test
