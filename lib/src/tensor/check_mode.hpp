#pragma once
// The mode argument check shared by the tensor operations (internal).
#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb::tensor::detail {

inline void check_mode(int mode, const char* where) {
    if (mode < 0 || mode > 2) {
        throw InvalidArgument(std::string(where) + ": mode must be 0 (dof), 1 (time) or 2 (sample), got " +
                              std::to_string(mode));
    }
}

}  // namespace mocapdb::tensor::detail
