#pragma once
// numpy <-> Eigen for the module: copies out of the library's matrices into new C-order arrays, and
// checked views of caller arrays. A column-major D x F matrix and a C-order (F, D) array share one
// memory layout, so pose vectors cross without a transpose.
#include <pybind11/numpy.h>

#include <cstring>
#include <string>

#include "bindings.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/core/types.hpp"

namespace mocapdb::python {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A new (rows, cols) array holding a row-major matrix's values.
inline Array copy_rows(const FrameMatrix& m) {
    Array out({m.rows(), m.cols()});
    if (m.size() > 0) std::memcpy(out.mutable_data(), m.data(), sizeof(double) * static_cast<std::size_t>(m.size()));
    return out;
}

/// A new (cols, rows) array holding a column-major matrix's columns as rows (D x F -> (F, D)).
inline Array copy_columns(const MatX& m) {
    Array out({m.cols(), m.rows()});
    if (m.size() > 0) std::memcpy(out.mutable_data(), m.data(), sizeof(double) * static_cast<std::size_t>(m.size()));
    return out;
}

inline Array copy_vector(const VecX& v) {
    Array out(v.size());
    if (v.size() > 0) std::memcpy(out.mutable_data(), v.data(), sizeof(double) * static_cast<std::size_t>(v.size()));
    return out;
}

/// The array as a vector of `expected` values (1-D); InvalidArgument naming `what` otherwise.
inline Eigen::Map<const VecX> vector_view(const Array& a, Eigen::Index expected, const char* what) {
    if (a.ndim() != 1 || a.shape(0) != expected)
        throw InvalidArgument(std::string(what) + ": expected a 1-D array of " + std::to_string(expected) + " values");
    return Eigen::Map<const VecX>(a.data(), expected);
}

/// A (rows, cols) C-order array as the column-major cols x rows matrix of the same memory.
inline Eigen::Map<const MatX> transposed_view(const Array& a, Eigen::Index cols, const char* what) {
    if (a.ndim() != 2 || a.shape(1) != cols)
        throw InvalidArgument(std::string(what) + ": expected a 2-D array with " + std::to_string(cols) + " columns");
    return Eigen::Map<const MatX>(a.data(), cols, a.shape(0));
}

}  // namespace mocapdb::python
