#pragma once
// Wall-clock seconds for timings the library reports (steady clock: never goes backwards).
#include <chrono>

namespace mocapdb {

using SteadyClock = std::chrono::steady_clock;

/// Seconds from `start` to now.
inline double seconds_since(SteadyClock::time_point start) {
    return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

}  // namespace mocapdb
