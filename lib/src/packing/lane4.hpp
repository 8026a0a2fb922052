#pragma once
// Four doubles as one vector value (GCC/Clang vector extension; internal to the packing module). Its
// arithmetic is IEEE lane by lane, so with -ffp-contract=off a lane computes exactly what the scalar
// expression computes: written where the compiler left a scalar loop unvectorized.
#include <cmath>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace mocapdb::packing::detail {

typedef double Lane4 __attribute__((vector_size(32)));

inline Lane4 load4(const double* p) {
    Lane4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

inline Lane4 splat(double v) { return Lane4{v, v, v, v}; }

// Lane-wise square root, correctly rounded as std::sqrt.
inline Lane4 sqrt4(Lane4 v) {
#if defined(__AVX__)
    return _mm256_sqrt_pd(v);
#else
    for (int i = 0; i < 4; ++i) v[i] = std::sqrt(v[i]);
    return v;
#endif
}

}  // namespace mocapdb::packing::detail
