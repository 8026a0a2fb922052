#include "gamma_vector.hpp"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace mocapdb::kriging::detail {

void gamma_vector(const Eigen::Ref<const Eigen::MatrixXd>& points, const VariogramModel& model,
                  const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out) {
    const Eigen::Index p = points.cols();
#if defined(__AVX2__)
    // One pass over the points (all P coordinates of 4 points at a time) instead of one per coordinate;
    // the same operations in the same order, so the same values.
    const Eigen::Index m = points.rows();
    const Eigen::Index stride = points.outerStride();  // between coordinates (columns)
    const double* pts = points.data();
    double* o = out.data();
    Eigen::Index i = 0;
    for (; i + 4 <= m; i += 4) {
        __m256d d = _mm256_sub_pd(_mm256_loadu_pd(pts + i), _mm256_set1_pd(c(0)));
        __m256d sum = _mm256_mul_pd(d, d);
        for (Eigen::Index k = 1; k < p; ++k) {
            d = _mm256_sub_pd(_mm256_loadu_pd(pts + k * stride + i), _mm256_set1_pd(c(k)));
            sum = _mm256_add_pd(sum, _mm256_mul_pd(d, d));
        }
        _mm256_storeu_pd(o + i, sum);
    }
    for (; i < m; ++i) {
        double d = pts[i] - c(0);
        double sum = d * d;
        for (Eigen::Index k = 1; k < p; ++k) {
            d = pts[k * stride + i] - c(k);
            sum += d * d;
        }
        o[i] = sum;
    }
#else
    out = (points.col(0).array() - c(0)).square().matrix();
    for (Eigen::Index d = 1; d < p; ++d) out.array() += (points.col(d).array() - c(d)).square();
#endif
    model.gamma_of_squared(out, out);
}

void gamma_block(const Eigen::MatrixXd& points, const VariogramModel& model,
                 const Eigen::Ref<const Eigen::MatrixXd>& queries, Eigen::Ref<Eigen::MatrixXd> out) {
    // Squared distances column by column (one query per column of out), then gamma on the whole block.
    const Eigen::Index p = points.cols();
    for (Eigen::Index q = 0; q < queries.rows(); ++q) {
        auto col = out.col(q).array();
        col = (points.col(0).array() - queries(q, 0)).square();
        for (Eigen::Index d = 1; d < p; ++d) col += (points.col(d).array() - queries(q, d)).square();
    }
    if (out.outerStride() == out.rows()) {
        const Eigen::Map<const Eigen::VectorXd> flat_in(out.data(), out.size());
        Eigen::Map<Eigen::VectorXd> flat_out(out.data(), out.size());
        model.gamma_of_squared(flat_in, flat_out);
    } else {
        for (Eigen::Index q = 0; q < out.cols(); ++q) model.gamma_of_squared(out.col(q), out.col(q));
    }
}

}  // namespace mocapdb::kriging::detail
