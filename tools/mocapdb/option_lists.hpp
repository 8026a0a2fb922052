#pragma once
// Comma-separated lists in command-line options ("x,y,z").
#include <string>
#include <vector>

namespace mocapdb::cli {

/// Splits "x,y,z" into {"x","y","z"} (whitespace trimmed; empty names rejected with InvalidArgument).
std::vector<std::string> split_names(const std::string& list, const std::string& option);

}  // namespace mocapdb::cli
