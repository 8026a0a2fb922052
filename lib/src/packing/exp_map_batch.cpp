#include "exp_map_batch.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "lane4.hpp"

namespace mocapdb::packing::detail {
namespace {
constexpr std::size_t kLanes = 16;  // exp_maps works in chunks of this many vectors

// Lane-wise square root, correctly rounded as std::sqrt.
inline Lane4 sqrt4(Lane4 v) {
#if defined(__AVX__)
    return _mm256_sqrt_pd(v);
#else
    for (int i = 0; i < 4; ++i) v[i] = std::sqrt(v[i]);
    return v;
#endif
}

// s[i], c[i] = sin, cos of a[i] >= 0 (half angles), i < n <= kLanes, four lanes at a time (a's
// entries up to the next multiple of 4 are read, and s's and c's written): a = j·π/2 + r,
// |r| <= π/4, r from three parts of π/2 (the first two with few significant bits, so j·part is exact
// for the angles met here), Cephes' sin/cos polynomials on r, the quadrant j mod 4 by selects. Every
// lane computes exactly what the scalar formulas compute (IEEE operations lane by lane, no
// contraction: -ffp-contract=off), written with vector types because the compiler left the scalar
// loop unvectorized.
void sin_cos(const double* a, std::size_t n, double* s, double* c) {
    constexpr double kTwoOverPi = 0.63661977236758134308;
    constexpr double kPio2a = 1.57079625129699707031;     // 2 · Cephes DP1
    constexpr double kPio2b = 7.54978941586159635336e-8;  // 2 · DP2
    constexpr double kPio2c = 5.39030285815811905290e-15; // 2 · DP3
    constexpr double kRound = 6755399441055744.0;         // 1.5 · 2^52: x + kRound - kRound rounds x
    for (std::size_t i = 0; i < n; i += 4) {
        const Lane4 x = load4(a + i);
        const Lane4 j = (x * kTwoOverPi + kRound) - kRound;
        const Lane4 r = ((x - j * kPio2a) - j * kPio2b) - j * kPio2c;
        const Lane4 z = r * r;
        const Lane4 ps = ((((1.58962301576546568060e-10 * z - 2.50507477628578072866e-8) * z + 2.75573136213857245213e-6) * z -
                           1.98412698295895385996e-4) * z + 8.33333333332211858878e-3) * z - 1.66666666666666307295e-1;
        const Lane4 pc = ((((-1.13585365213876817300e-11 * z + 2.08757008419747316778e-9) * z - 2.75573141792967388112e-7) * z +
                           2.48015872888517045348e-5) * z - 1.38888888888730564116e-3) * z + 4.16666666666665929218e-2;
        const Lane4 sr = r + r * z * ps;
        const Lane4 cr = 1.0 - 0.5 * z + z * z * pc;
        // j mod 4 (j >= 0, a whole number): j/4 has a fraction of 0, 1/4, 1/2 or 3/4, so j/4 - 3/8
        // rounded to the nearest whole number is floor(j/4), exactly.
        const Lane4 q = j - 4.0 * (((j * 0.25 - 0.375) + kRound) - kRound);
        // q in {0, 1, 2, 3}: (sin, cos) = (sr, cr), (cr, -sr), (-sr, -cr), (-cr, sr)
        const auto odd = (q == 1.0) | (q == 3.0);
        const Lane4 sv = odd ? cr : sr;
        const Lane4 cv = odd ? sr : cr;
        const Lane4 sl = q >= 2.0 ? -sv : sv;
        const Lane4 cl = ((q == 1.0) | (q == 2.0)) ? -cv : cv;
        std::memcpy(s + i, &sl, sizeof sl);
        std::memcpy(c + i, &cl, sizeof cl);
    }
}

}  // namespace

void exp_maps(const double* x, const double* y, const double* z, std::size_t n, Quat* out) {
    // Whole lanes of 4 throughout (zero-padded inputs); each lane computes what the scalar
    // formulas compute, bit for bit.
    double xs[kLanes], ys[kLanes], zs[kLanes], angle[kLanes], half[kLanes], s[kLanes], c[kLanes], f[kLanes];
    for (std::size_t i0 = 0; i0 < n; i0 += kLanes) {
        const std::size_t m = n - i0 < kLanes ? n - i0 : kLanes;
        for (std::size_t i = 0; i < kLanes; ++i) {
            xs[i] = i < m ? x[i0 + i] : 0.0;
            ys[i] = i < m ? y[i0 + i] : 0.0;
            zs[i] = i < m ? z[i0 + i] : 0.0;
        }
        for (std::size_t i = 0; i < m; i += 4) {
            const Lane4 a = load4(xs + i), b = load4(ys + i), d = load4(zs + i);
            const Lane4 root = sqrt4(a * a + b * b + d * d);
            const Lane4 h = 0.5 * root;
            std::memcpy(angle + i, &root, sizeof root);
            std::memcpy(half + i, &h, sizeof h);
        }
        sin_cos(half, m, s, c);
        for (std::size_t i = 0; i < m; i += 4) {
            const Lane4 a = load4(angle + i);
            const Lane4 q = load4(s + i) / (a < 1e-12 ? Lane4{1.0, 1.0, 1.0, 1.0} : a);  // tiny angles: below
            std::memcpy(f + i, &q, sizeof q);
        }
        for (std::size_t i = 0; i < m; ++i) {
            const std::size_t k = i0 + i;
            if (angle[i] < 1e-12) {  // as exp_map: the second-order series, normalized
                out[k] = Quat(1.0 - angle[i] * angle[i] / 8.0, 0.5 * x[k], 0.5 * y[k], 0.5 * z[k]).normalized();
                continue;
            }
            out[k] = Quat(c[i], f[i] * x[k], f[i] * y[k], f[i] * z[k]);
        }
    }
}

}  // namespace mocapdb::packing::detail
