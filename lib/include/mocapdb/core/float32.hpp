#pragma once
// Rounding to float32 for values a file stores as float32, done so that the compiler keeps it.
//
// GCC 12.2 at -O2 and above (its tree vectorizer) was seen to fold the double -> float -> double
// round trip of Eigen vectors held in a std::vector into the identity: the values stayed unrounded
// (a small program reproduces it; -O1 or -fno-tree-vectorize round them). An encoder that checks its
// bound against values it takes for float32 while the decoder reads the real float32 values then
// misses the bound by up to about 1e-5 cm (packed skeleton offsets; docs/packing.md). A volatile
// float makes the conversion observable, so it cannot be folded. It costs a store and a load per
// value: meant for headers, skeletons and models, not for per-sample hot loops.
// Thread-safe; no errors (values outside float32's range become ±inf, NaN stays NaN).
#include "mocapdb/core/types.hpp"

namespace mocapdb {

/// x rounded to the nearest float32 (ties to even).
inline float to_float32(double x) {
    volatile float f = static_cast<float>(x);
    return f;
}

/// x rounded to the nearest float32, as a double.
inline double float32_value(double x) { return static_cast<double>(to_float32(x)); }

/// Every entry of m rounded to the nearest float32 (in place).
template <typename Derived>
void round_entries_to_float32(Eigen::DenseBase<Derived>& m) {
    for (Eigen::Index j = 0; j < m.cols(); ++j)
        for (Eigen::Index i = 0; i < m.rows(); ++i) m(i, j) = float32_value(m(i, j));
}

}  // namespace mocapdb
