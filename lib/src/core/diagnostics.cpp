#include "mocapdb/core/diagnostics.hpp"

namespace mocapdb {

std::string Warning::to_string() const {
    std::string out = file;
    if (line > 0) out += ":" + std::to_string(line);
    return out + ": " + message;
}

}  // namespace mocapdb
