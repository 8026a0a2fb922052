#include "mocapdb/io/frame_rate.hpp"

#include <cstdio>

#include "mocapdb/core/error.hpp"

namespace mocapdb {

std::string frame_rate_problem(double rate) {
    if (rate > 0.0 && rate <= kMaxFrameRate) return {};  // false for NaN
    char text[64];
    std::snprintf(text, sizeof text, "%g", rate);
    return "frame rate must be > 0 and <= " + std::to_string(static_cast<int>(kMaxFrameRate)) + " Hz, got " + text;
}

void check_frame_rate(double rate, const std::string& what) {
    const std::string problem = frame_rate_problem(rate);
    if (!problem.empty()) throw InvalidArgument(what + ": " + problem);
}

}  // namespace mocapdb
