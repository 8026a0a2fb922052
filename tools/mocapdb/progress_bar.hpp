#pragma once
// A one-line progress bar on stderr, drawn only when both stdout and stderr are terminals (silent in
// pipes, redirections, scripts and tests: stdout is never touched). Fed by the library's
// ProgressCallback. Every command that can take over a second on real data draws one.
#include <chrono>
#include <string>

#include "mocapdb/core/progress.hpp"

namespace mocapdb::cli {

class ProgressBar {
public:
    /// `label` starts the line ("import").
    explicit ProgressBar(std::string label);
    /// Clears the line when it was drawn.
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    bool enabled() const noexcept { return enabled_; }
    /// A callback that redraws the bar (at most ~10 times a second); empty when disabled.
    ProgressCallback callback();
    void update(const Progress& p);
    /// Erases the bar (before printing other lines).
    void clear();

private:
    std::string label_;
    bool enabled_ = false;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point last_{};
    std::chrono::steady_clock::time_point start_;
};

}  // namespace mocapdb::cli
