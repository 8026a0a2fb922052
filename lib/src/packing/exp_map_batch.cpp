#include "exp_map_batch.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "lane4.hpp"
#include "mocapdb/core/types.hpp"

namespace mocapdb::packing::detail {
namespace {

// s, c = sin, cos of x >= 0 (half angles), lane by lane: x = j·π/2 + r, |r| <= π/4, r from three
// parts of π/2 (the first two with few significant bits, so j·part is exact for the angles met here),
// Cephes' sin/cos polynomials on r, the quadrant j mod 4 by selects. Every lane computes exactly what
// the scalar formulas compute (IEEE operations lane by lane, no contraction: -ffp-contract=off),
// written with vector types because the compiler left the scalar loop unvectorized.
inline void sin_cos(Lane4 x, Lane4& s, Lane4& c) {
    constexpr double kTwoOverPi = 0.63661977236758134308;
    constexpr double kPio2a = 1.57079625129699707031;      // 2 · Cephes DP1
    constexpr double kPio2b = 7.54978941586159635336e-8;   // 2 · DP2
    constexpr double kPio2c = 5.39030285815811905290e-15;  // 2 · DP3
    constexpr double kRound = 6755399441055744.0;          // 1.5 · 2^52: x + kRound - kRound rounds x
    const Lane4 j = (x * kTwoOverPi + kRound) - kRound;
    const Lane4 r = ((x - j * kPio2a) - j * kPio2b) - j * kPio2c;
    const Lane4 z = r * r;
    const Lane4 ps =
        ((((1.58962301576546568060e-10 * z - 2.50507477628578072866e-8) * z + 2.75573136213857245213e-6) * z -
          1.98412698295895385996e-4) *
             z +
         8.33333333332211858878e-3) *
            z -
        1.66666666666666307295e-1;
    const Lane4 pc =
        ((((-1.13585365213876817300e-11 * z + 2.08757008419747316778e-9) * z - 2.75573141792967388112e-7) * z +
          2.48015872888517045348e-5) *
             z -
         1.38888888888730564116e-3) *
            z +
        4.16666666666665929218e-2;
    const Lane4 sr = r + r * z * ps;
    const Lane4 cr = 1.0 - 0.5 * z + z * z * pc;
    // j mod 4 (j >= 0, a whole number): j/4 has a fraction of 0, 1/4, 1/2 or 3/4, so j/4 - 3/8
    // rounded to the nearest whole number is floor(j/4), exactly.
    const Lane4 q = j - 4.0 * (((j * 0.25 - 0.375) + kRound) - kRound);
    // q in {0, 1, 2, 3}: (sin, cos) = (sr, cr), (cr, -sr), (-sr, -cr), (-cr, sr)
    const auto odd = (q == 1.0) | (q == 3.0);
    const Lane4 sv = odd ? cr : sr;
    const Lane4 cv = odd ? sr : cr;
    s = q >= 2.0 ? -sv : sv;
    c = ((q == 1.0) | (q == 2.0)) ? -cv : cv;
}

}  // namespace

void exp_maps(Lane4 x, Lane4 y, Lane4 z, Lane4& w, Lane4& qx, Lane4& qy, Lane4& qz) {
    const Lane4 angle = sqrt4(x * x + y * y + z * z);
    Lane4 s, c;
    sin_cos(0.5 * angle, s, c);
    const auto tiny = angle < 1e-12;
    const Lane4 f = s / (tiny ? Lane4{1.0, 1.0, 1.0, 1.0} : angle);
    w = c;
    qx = f * x;
    qy = f * y;
    qz = f * z;
    for (int l = 0; l < 4; ++l)
        if (tiny[l] != 0) {  // as exp_map: the second-order series, normalized
            const Quat q = Quat(1.0 - angle[l] * angle[l] / 8.0, 0.5 * x[l], 0.5 * y[l], 0.5 * z[l]).normalized();
            w[l] = q.w();
            qx[l] = q.x();
            qy[l] = q.y();
            qz[l] = q.z();
        }
}

}  // namespace mocapdb::packing::detail
