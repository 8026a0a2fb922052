#include "exp_map_batch.hpp"

#include <cmath>
#include <cstdint>

namespace mocapdb::packing::detail {
namespace {
constexpr std::size_t kLanes = 16;  // exp_maps works in chunks of this many vectors

// s[i], c[i] = sin, cos of a[i] >= 0 (half angles), i < n <= kLanes: a = j·π/2 + r, |r| <= π/4, r
// from three parts of π/2 (the first two with few significant bits, so j·part is exact for the
// angles met here), Cephes' sin/cos polynomials on r, the quadrant j mod 4 by selects. Branch-free
// so that the compiler vectorizes it.
void sin_cos(const double* a, std::size_t n, double* s, double* c) {
    constexpr double kTwoOverPi = 0.63661977236758134308;
    constexpr double kPio2a = 1.57079625129699707031;     // 2 · Cephes DP1
    constexpr double kPio2b = 7.54978941586159635336e-8;  // 2 · DP2
    constexpr double kPio2c = 5.39030285815811905290e-15; // 2 · DP3
    constexpr double kRound = 6755399441055744.0;         // 1.5 · 2^52: x + kRound - kRound rounds x
    for (std::size_t i = 0; i < n; ++i) {
        const double j = (a[i] * kTwoOverPi + kRound) - kRound;
        const double r = ((a[i] - j * kPio2a) - j * kPio2b) - j * kPio2c;
        const double z = r * r;
        const double ps = ((((1.58962301576546568060e-10 * z - 2.50507477628578072866e-8) * z + 2.75573136213857245213e-6) * z -
                            1.98412698295895385996e-4) * z + 8.33333333332211858878e-3) * z - 1.66666666666666307295e-1;
        const double pc = ((((-1.13585365213876817300e-11 * z + 2.08757008419747316778e-9) * z - 2.75573141792967388112e-7) * z +
                            2.48015872888517045348e-5) * z - 1.38888888888730564116e-3) * z + 4.16666666666665929218e-2;
        const double sr = r + r * z * ps;
        const double cr = 1.0 - 0.5 * z + z * z * pc;
        const double q = j - 4.0 * std::floor(j * 0.25);  // j >= 0
        // q = j mod 4 in {0, 1, 2, 3}: (sin, cos) = (sr, cr), (cr, -sr), (-sr, -cr), (-cr, sr)
        const bool odd = q == 1.0 || q == 3.0;
        const double sv = odd ? cr : sr;
        const double cv = odd ? sr : cr;
        s[i] = q >= 2.0 ? -sv : sv;
        c[i] = (q == 1.0 || q == 2.0) ? -cv : cv;
    }
}

}  // namespace

void exp_maps(const double* x, const double* y, const double* z, std::size_t n, Quat* out) {
    double angle[kLanes], half[kLanes], s[kLanes], c[kLanes];
    for (std::size_t i0 = 0; i0 < n; i0 += kLanes) {
        const std::size_t m = n - i0 < kLanes ? n - i0 : kLanes;
        for (std::size_t i = 0; i < m; ++i) {
            const std::size_t k = i0 + i;
            angle[i] = std::sqrt(x[k] * x[k] + y[k] * y[k] + z[k] * z[k]);
            half[i] = 0.5 * angle[i];
        }
        sin_cos(half, m, s, c);
        for (std::size_t i = 0; i < m; ++i) {
            const std::size_t k = i0 + i;
            if (angle[i] < 1e-12) {  // as exp_map: the second-order series, normalized
                out[k] = Quat(1.0 - angle[i] * angle[i] / 8.0, 0.5 * x[k], 0.5 * y[k], 0.5 * z[k]).normalized();
                continue;
            }
            const double f = s[i] / angle[i];
            out[k] = Quat(c[i], f * x[k], f * y[k], f * z[k]);
        }
    }
}

}  // namespace mocapdb::packing::detail
