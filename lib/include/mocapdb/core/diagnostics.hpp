#pragma once
// Non-fatal findings of a reader (a defect it worked around). The library never prints: callers
// decide whether to show warnings, and strict modes turn them into errors instead.
#include <string>
#include <vector>

namespace mocapdb {

struct Warning {
    std::string file;
    std::size_t line = 0;  ///< 1-based; 0 when the warning is not tied to a line
    std::string message;
    /// "FILE:LINE: MESSAGE", the same shape as a ParseError.
    std::string to_string() const;
};

using Warnings = std::vector<Warning>;

}  // namespace mocapdb
