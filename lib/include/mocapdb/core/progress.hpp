#pragma once
// Progress reporting from long library operations. The library never prints: it calls a callback the
// caller supplies (the CLI draws a bar on a terminal, tests and scripts pass nothing).
#include <cstdint>
#include <functional>
#include <string_view>

namespace mocapdb {

/// One progress report. `done` and `total` are in the operation's own unit (bytes for an import);
/// `total` is 0 when unknown. `item` names what is being worked on (a file name) and is only valid
/// during the call.
struct Progress {
    std::uint64_t done = 0;
    std::uint64_t total = 0;
    std::string_view item;
};

/// Called from the working thread, at most a few times per item; must not throw. May be empty.
using ProgressCallback = std::function<void(const Progress&)>;

}  // namespace mocapdb
