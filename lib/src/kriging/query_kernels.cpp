#include "query_kernels.hpp"

#ifdef MOCAPDB_KRIGING_QUERY_KERNELS

#include <immintrin.h>

#include <algorithm>

#include "mocapdb/core/huge_pages.hpp"

namespace mocapdb::kriging::detail {

Eigen::VectorXd pack_symmetric(const Eigen::Ref<const Eigen::MatrixXd>& a, double sign) {
    const Eigen::Index m = a.rows();
    const Eigen::Index nb = padded_size(m) / 4;
    Eigen::VectorXd packed(nb * (nb + 1) / 2 * 16);
    advise_huge_pages(packed);
    Eigen::Index o = 0;
    for (Eigen::Index bi = 0; bi < nb; ++bi) {
        for (Eigen::Index bj = 0; bj <= bi; ++bj) {
            for (Eigen::Index r = 0; r < 4; ++r) {
                for (Eigen::Index c = 0; c < 4; ++c) {
                    const Eigen::Index i = 4 * bi + r;
                    const Eigen::Index j = 4 * bj + c;
                    // a(j, i) = a(i, j): down four columns at a time (a(i, j) would stride across them)
                    packed(o++) = i < m && j < m ? sign * a(j, i) : 0.0;
                }
            }
        }
    }
    return packed;
}

namespace {

// Keeps v in a register: without it GCC 12 folds the block's loads into the memory operands of both of
// their FMAs, loading every block twice and x_J four times (measured 6.4 instead of 4.3 cycles per
// block).
#define MOCAPDB_KEEP_IN_REGISTER(v) __asm__("" : "+x"(v))

// (sum of a0, sum of a1, sum of a2, sum of a3).
inline __m256d horizontal_sums(__m256d a0, __m256d a1, __m256d a2, __m256d a3) {
    const __m256d s01 = _mm256_hadd_pd(a0, a1);  // a0[0]+a0[1], a1[0]+a1[1], a0[2]+a0[3], a1[2]+a1[3]
    const __m256d s23 = _mm256_hadd_pd(a2, a3);
    return _mm256_add_pd(_mm256_permute2f128_pd(s01, s23, 0x20), _mm256_permute2f128_pd(s01, s23, 0x31));
}

// The column kernels below take up to kMaxColumns columns per pass: K = 1 + P for a linear trend, so
// one pass for up to 5 control dimensions (2 K accumulators of dot_columns fit the 16 registers).
constexpr int kMaxColumns = 6;

// dst = src + sum_{k < NK} coef_k col_k (src == nullptr: 0), col_k = cols + k mp, over mp values 4 at a
// time, of which the first n are written (n <= mp; src may be dst). The coefficients are broadcast once
// (a runtime loop over k re-loaded them for every vector).
template <int NK>
void add_columns(const double* cols, Eigen::Index mp, const double* coef, const double* src, double* dst,
                 Eigen::Index n) {
    __m256d c[NK];
    for (int k = 0; k < NK; ++k) c[k] = _mm256_broadcast_sd(coef + k);
    for (Eigen::Index i = 0; i < mp; i += 4) {
        __m256d v = src != nullptr ? _mm256_loadu_pd(src + i) : _mm256_setzero_pd();
        for (int k = 0; k < NK; ++k) v = _mm256_fmadd_pd(c[k], _mm256_loadu_pd(cols + k * mp + i), v);
        if (i + 4 <= n) {
            _mm256_storeu_pd(dst + i, v);
        } else if (i < n) {  // the last 1 to 3 values
            alignas(32) double tail[4];
            _mm256_store_pd(tail, v);
            std::copy(tail, tail + (n - i), dst + i);
        }
    }
}

// The same for any number kk >= 1 of columns, kMaxColumns per pass: with more than kMaxColumns, dst
// holds the running sum, so it must then have all mp values.
void add_columns(const double* cols, Eigen::Index mp, Eigen::Index kk, const double* coef, const double* src,
                 double* dst, Eigen::Index n) {
    for (Eigen::Index k = 0; k < kk; k += kMaxColumns) {
        const double* in = k == 0 ? src : dst;
        const Eigen::Index n_out = k + kMaxColumns >= kk ? n : mp;
        switch (std::min<Eigen::Index>(kMaxColumns, kk - k)) {
            case 1: add_columns<1>(cols + k * mp, mp, coef + k, in, dst, n_out); break;
            case 2: add_columns<2>(cols + k * mp, mp, coef + k, in, dst, n_out); break;
            case 3: add_columns<3>(cols + k * mp, mp, coef + k, in, dst, n_out); break;
            case 4: add_columns<4>(cols + k * mp, mp, coef + k, in, dst, n_out); break;
            case 5: add_columns<5>(cols + k * mp, mp, coef + k, in, dst, n_out); break;
            default: add_columns<6>(cols + k * mp, mp, coef + k, in, dst, n_out); break;
        }
    }
}

// out_k = col_k^T v for k < NK, col_k = cols + k mp, over mp values; two accumulators per column (even
// and odd vectors of v: half the dependency chain).
template <int NK>
void dot_columns(const double* cols, Eigen::Index mp, const double* v, double* out) {
    __m256d s[NK];
    __m256d t[NK];
    for (int k = 0; k < NK; ++k) s[k] = t[k] = _mm256_setzero_pd();
    Eigen::Index i = 0;
    for (; i + 8 <= mp; i += 8) {
        const __m256d ve = _mm256_loadu_pd(v + i);
        const __m256d vo = _mm256_loadu_pd(v + i + 4);
        for (int k = 0; k < NK; ++k) {
            s[k] = _mm256_fmadd_pd(_mm256_loadu_pd(cols + k * mp + i), ve, s[k]);
            t[k] = _mm256_fmadd_pd(_mm256_loadu_pd(cols + k * mp + i + 4), vo, t[k]);
        }
    }
    if (i < mp) {
        const __m256d ve = _mm256_loadu_pd(v + i);
        for (int k = 0; k < NK; ++k) s[k] = _mm256_fmadd_pd(_mm256_loadu_pd(cols + k * mp + i), ve, s[k]);
    }
    for (int k0 = 0; k0 < NK; k0 += 4) {
        __m256d r[4];
        for (int j = 0; j < 4; ++j) r[j] = k0 + j < NK ? _mm256_add_pd(s[k0 + j], t[k0 + j]) : _mm256_setzero_pd();
        alignas(32) double sums[4];
        _mm256_store_pd(sums, horizontal_sums(r[0], r[1], r[2], r[3]));
        for (int j = 0; j < 4 && k0 + j < NK; ++j) out[k0 + j] = sums[j];
    }
}

// The same for any number kk >= 1 of columns.
void dot_columns(const double* cols, Eigen::Index mp, Eigen::Index kk, const double* v, double* out) {
    for (Eigen::Index k = 0; k < kk; k += kMaxColumns) {
        switch (std::min<Eigen::Index>(kMaxColumns, kk - k)) {
            case 1: dot_columns<1>(cols + k * mp, mp, v, out + k); break;
            case 2: dot_columns<2>(cols + k * mp, mp, v, out + k); break;
            case 3: dot_columns<3>(cols + k * mp, mp, v, out + k); break;
            case 4: dot_columns<4>(cols + k * mp, mp, v, out + k); break;
            case 5: dot_columns<5>(cols + k * mp, mp, v, out + k); break;
            default: dot_columns<6>(cols + k * mp, mp, v, out + k); break;
        }
    }
}

}  // namespace

void packed_symmetric_product(const Eigen::VectorXd& packed, const Eigen::MatrixXd& t, const double* x, const double* g,
                              double* y) {
    const Eigen::Index mp = t.rows();
    const Eigen::Index kk = t.cols();
    // y = T g first, a pass of its own (inside the loop below it cost more).
    add_columns(t.data(), mp, kk, g, nullptr, y, mp);
    const double* block = packed.data();
    // Row block I: its row sums over the blocks left of the diagonal accumulate in a0..a3 (one register
    // per row, reduced at the end), while the transposed blocks update y_J, J < I, in memory. y_I gets
    // its row sums here and the column sums of the transposed blocks from the rows below it.
    for (Eigen::Index bi = 0; bi < mp / 4; ++bi) {
        const double* xi = x + 4 * bi;
        const __m256d b0 = _mm256_broadcast_sd(xi);
        const __m256d b1 = _mm256_broadcast_sd(xi + 1);
        const __m256d b2 = _mm256_broadcast_sd(xi + 2);
        const __m256d b3 = _mm256_broadcast_sd(xi + 3);
        __m256d a0 = _mm256_setzero_pd();
        __m256d a1 = a0;
        __m256d a2 = a0;
        __m256d a3 = a0;
        for (Eigen::Index bj = 0; bj < bi; ++bj, block += 16) {
            __m256d p0 = _mm256_loadu_pd(block);
            __m256d p1 = _mm256_loadu_pd(block + 4);
            __m256d p2 = _mm256_loadu_pd(block + 8);
            __m256d p3 = _mm256_loadu_pd(block + 12);
            __m256d x_j = _mm256_loadu_pd(x + 4 * bj);
            MOCAPDB_KEEP_IN_REGISTER(p0);
            MOCAPDB_KEEP_IN_REGISTER(p1);
            MOCAPDB_KEEP_IN_REGISTER(p2);
            MOCAPDB_KEEP_IN_REGISTER(p3);
            MOCAPDB_KEEP_IN_REGISTER(x_j);
            a0 = _mm256_fmadd_pd(p0, x_j, a0);
            a1 = _mm256_fmadd_pd(p1, x_j, a1);
            a2 = _mm256_fmadd_pd(p2, x_j, a2);
            a3 = _mm256_fmadd_pd(p3, x_j, a3);
            __m256d y_j = _mm256_loadu_pd(y + 4 * bj);
            y_j = _mm256_fmadd_pd(p0, b0, y_j);
            y_j = _mm256_fmadd_pd(p1, b1, y_j);
            y_j = _mm256_fmadd_pd(p2, b2, y_j);
            y_j = _mm256_fmadd_pd(p3, b3, y_j);
            _mm256_storeu_pd(y + 4 * bj, y_j);
        }
        // Diagonal block (stored in full).
        const __m256d x_i = _mm256_loadu_pd(xi);
        a0 = _mm256_fmadd_pd(_mm256_loadu_pd(block), x_i, a0);
        a1 = _mm256_fmadd_pd(_mm256_loadu_pd(block + 4), x_i, a1);
        a2 = _mm256_fmadd_pd(_mm256_loadu_pd(block + 8), x_i, a2);
        a3 = _mm256_fmadd_pd(_mm256_loadu_pd(block + 12), x_i, a3);
        block += 16;
        _mm256_storeu_pd(y + 4 * bi, _mm256_add_pd(_mm256_loadu_pd(y + 4 * bi), horizontal_sums(a0, a1, a2, a3)));
    }
}

#undef MOCAPDB_KEEP_IN_REGISTER

namespace {

Eigen::MatrixXd pad_rows(const Eigen::Ref<const Eigen::MatrixXd>& a) {
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(padded_size(a.rows()), a.cols());
    out.topRows(a.rows()) = a;
    return out;
}

}  // namespace

QueryOperator::QueryOperator(const Eigen::Ref<const Eigen::MatrixXd>& wc, const Eigen::Ref<const Eigen::MatrixXd>& v,
                             const Eigen::Ref<const Eigen::MatrixXd>& g)
    : m(wc.rows()),
      kernel(pack_symmetric(wc, -1.0)),
      trend(pad_rows(v)),
      basis(pad_rows(g)),
      basis_sums(basis.colwise().sum().transpose()) {}

void QueryOperator::weights(const double* gamma, const double* g, double* b, double* corr, double* w) const {
    const Eigen::Index mp = padded_size();
    const Eigen::Index kk = basis_size();
    packed_symmetric_product(kernel, trend, gamma, g, b);
    // corr = D (g - G^T b), D = diag(1 / M, 1, ...), then w = b + G corr. The constant's correction
    // also takes out what the U corrections add to the sum (sum_i U_ik = 0 only up to rounding, and for
    // OLS the U corrections are the trend correction, of the size of the weights).
    dot_columns(basis.data(), mp, kk, b, corr);
    double c0 = g[0] - corr[0];
    for (Eigen::Index k = 1; k < kk; ++k) {
        corr[k] = g[k] - corr[k];
        c0 -= corr[k] * basis_sums(k);
    }
    corr[0] = c0 / static_cast<double>(m);
    if (kk <= kMaxColumns) {
        add_columns(basis.data(), mp, kk, corr, b, w, m);
    } else {  // more than 5 control dimensions: several passes over b, then w
        add_columns(basis.data(), mp, kk, corr, b, b, mp);
        if (w != b) std::copy(b, b + m, w);
    }
}

}  // namespace mocapdb::kriging::detail

#endif
