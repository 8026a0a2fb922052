#pragma once
// Internal: text helpers shared by the ASF and AMC readers.
#include <string>
#include <string_view>

namespace mocapdb::detail {

/// A copy of `text` with every '#' comment (to the end of its line) replaced by spaces. Lines and
/// columns are unchanged, so the scanner reports positions in the original text and never sees a comment.
std::string blank_comments(std::string_view text);

/// ASCII case-insensitive equality (Acclaim keywords are written in either case).
bool iequals(std::string_view a, std::string_view b) noexcept;

}  // namespace mocapdb::detail
