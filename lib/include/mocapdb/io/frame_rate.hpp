#pragma once
// The frame rate a user may give instead of a file's own (readers' frame_rate options, `--fps`).
#include <string>

namespace mocapdb {

/// Largest frame rate accepted as an override, Hz (capture systems run at up to a few kHz).
inline constexpr double kMaxFrameRate = 10000.0;

/// "" when `rate` is finite and in (0, kMaxFrameRate], else "frame rate must be > 0 and <= 10000 Hz,
/// got X" (X as %g).
std::string frame_rate_problem(double rate);

/// InvalidArgument "`what`: " + frame_rate_problem(rate) unless that is empty.
void check_frame_rate(double rate, const std::string& what);

}  // namespace mocapdb
