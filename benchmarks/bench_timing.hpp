#pragma once
// Timing helpers shared by the benchmark programs. The machine is shared and noisy: programs report
// the best (least disturbed) of several repeats, and the median beside it where useful.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

namespace mocapdb::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// CPU seconds of the calling thread (CLOCK_THREAD_CPUTIME_ID): unlike wall time, not inflated by
/// other processes taking the core (cache sharing with them still shows).
inline double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

inline double wall_seconds() { return std::chrono::duration<double>(Clock::now().time_since_epoch()).count(); }

inline double best(std::vector<double> v) { return *std::min_element(v.begin(), v.end()); }

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

/// Best of `repeats` timings of fn(), seconds.
template <class F>
double best_of(int repeats, F fn) {
    double result = 1e300;
    for (int r = 0; r < repeats; ++r) {
        const auto t = Clock::now();
        fn();
        result = std::min(result, seconds_since(t));
    }
    return result;
}

/// "1,0.5,0.1" -> {1, 0.5, 0.1} (std::invalid_argument on a bad number).
inline std::vector<double> parse_doubles(const std::string& text) {
    std::vector<double> out;
    std::stringstream ss(text);
    for (std::string t; std::getline(ss, t, ',');) out.push_back(std::stod(t));
    return out;
}

/// "a,b,,c" -> {"a", "b", "c"} (empty items dropped).
inline std::vector<std::string> split_list(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream ss(text);
    for (std::string item; std::getline(ss, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

/// Written by benchmarks so the compiler cannot drop the measured work.
inline volatile double g_sink = 0.0;

}  // namespace mocapdb::bench
