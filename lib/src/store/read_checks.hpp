#pragma once
// Checks of what a codec reads back from a file, shared by the codecs: a dataset's shape and its values'
// finiteness. A failed check is damage, refused where it is read with a StoreError naming the file and
// the HDF5 path (so a writing session that reads it publishes nothing).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "h5/file.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store {

[[noreturn]] inline void shape_error(const h5::File& file, const std::string& path, const h5::Shape& expected,
                                     const std::string& why, const h5::Shape& found) {
    throw StoreError(file.name(), path,
                     "expected shape " + h5::shape_text(expected) + " " + why + ", found " + h5::shape_text(found));
}

inline void expect_shape(const h5::File& file, const std::string& path, const h5::Shape& expected,
                         const std::string& why, const h5::Shape& found) {
    if (found != expected) shape_error(file, path, expected, why, found);
}

inline void expect_finite(const h5::File& file, const std::string& path, const double* begin, const double* end) {
    const double* it = std::find_if(begin, end, [](double x) { return !std::isfinite(x); });
    if (it != end)
        throw StoreError(file.name(), path,
                         "expected finite values, found " + std::to_string(*it) + " at element " +
                             std::to_string(it - begin) + " (C order)");
}

inline void expect_finite(const h5::File& file, const std::string& path, const std::vector<double>& values) {
    expect_finite(file, path, values.data(), values.data() + values.size());
}

}  // namespace mocapdb::store
