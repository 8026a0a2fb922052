#include "exp_map_batch.hpp"

#include <cmath>
#include <cstdint>

namespace mocapdb::packing::detail {
namespace {

// sin and cos of a >= 0 (a half angle): a = j·π/2 + r, |r| <= π/4, r from three parts of π/2 (the
// first two with few significant bits, so j·part is exact for the angles met here), then Cephes'
// sin/cos polynomials on r and the quadrant j mod 4.
inline void sin_cos(double a, double& s, double& c) {
    constexpr double kTwoOverPi = 0.63661977236758134308;
    constexpr double kPio2a = 1.57079625129699707031;     // 2 · Cephes DP1
    constexpr double kPio2b = 7.54978941586159635336e-8;  // 2 · DP2
    constexpr double kPio2c = 5.39030285815811905290e-15; // 2 · DP3
    const double j = std::nearbyint(a * kTwoOverPi);
    const double r = ((a - j * kPio2a) - j * kPio2b) - j * kPio2c;
    const double z = r * r;
    const double ps = ((((1.58962301576546568060e-10 * z - 2.50507477628578072866e-8) * z + 2.75573136213857245213e-6) * z -
                        1.98412698295895385996e-4) * z + 8.33333333332211858878e-3) * z - 1.66666666666666307295e-1;
    const double pc = ((((-1.13585365213876817300e-11 * z + 2.08757008419747316778e-9) * z - 2.75573141792967388112e-7) * z +
                        2.48015872888517045348e-5) * z - 1.38888888888730564116e-3) * z + 4.16666666666665929218e-2;
    const double sr = r + r * z * ps;
    const double cr = 1.0 - 0.5 * z + z * z * pc;
    switch (static_cast<std::int64_t>(j) & 3) {
        case 0: s = sr; c = cr; break;
        case 1: s = cr; c = -sr; break;
        case 2: s = -sr; c = -cr; break;
        default: s = -cr; c = sr; break;
    }
}

}  // namespace

void exp_maps(const double* x, const double* y, const double* z, std::size_t n, Quat* out) {
    for (std::size_t i = 0; i < n; ++i) {
        const double angle = std::sqrt(x[i] * x[i] + y[i] * y[i] + z[i] * z[i]);
        if (angle < 1e-12) {  // as exp_map: the second-order series, normalized
            Quat q(1.0 - angle * angle / 8.0, 0.5 * x[i], 0.5 * y[i], 0.5 * z[i]);
            out[i] = q.normalized();
            continue;
        }
        double s, c;
        sin_cos(0.5 * angle, s, c);
        const double f = s / angle;
        out[i] = Quat(c, f * x[i], f * y[i], f * z[i]);
    }
}

}  // namespace mocapdb::packing::detail
