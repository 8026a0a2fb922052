#pragma once
// Four doubles as one vector value (GCC/Clang vector extension; internal to the packing module). Its
// arithmetic is IEEE lane by lane, so with -ffp-contract=off a lane computes exactly what the scalar
// expression computes: written where the compiler left a scalar loop unvectorized.
#include <cstring>

namespace mocapdb::packing::detail {

typedef double Lane4 __attribute__((vector_size(32)));

inline Lane4 load4(const double* p) {
    Lane4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

}  // namespace mocapdb::packing::detail
