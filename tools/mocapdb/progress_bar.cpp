#include "progress_bar.hpp"

#include <unistd.h>

#include <cstdio>

namespace mocapdb::cli {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)),
      enabled_(::isatty(STDOUT_FILENO) == 1 && ::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() { clear(); }

ProgressCallback ProgressBar::callback() {
    if (!enabled_) return {};
    return [this](const Progress& p) { update(p); };
}

void ProgressBar::update(const Progress& p) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    const bool finished = p.total > 0 && p.done >= p.total;
    if (drawn_ && !finished && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    constexpr int width = 30;
    const double fraction = p.total > 0 ? static_cast<double>(p.done) / static_cast<double>(p.total) : 0.0;
    const int filled = static_cast<int>(fraction * width + 0.5);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    const double seconds = std::chrono::duration<double>(now - start_).count();
    std::string item(p.item.substr(0, 32));
    std::fprintf(stderr, "\r%s [%s] %3.0f%% %6.1f s  %-32s", label_.c_str(), bar.c_str(), 100.0 * fraction, seconds,
                 item.c_str());
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressBar::clear() {
    if (!drawn_) return;
    std::fprintf(stderr, "\r%*s\r", 90, "");
    std::fflush(stderr);
    drawn_ = false;
}

}  // namespace mocapdb::cli
