#include "asf_text.hpp"

namespace mocapdb::detail {

std::string blank_comments(std::string_view text) {
    std::string out(text);
    bool in_comment = false;
    for (char& c : out) {
        if (c == '\n') {
            in_comment = false;
        } else if (c == '#') {
            in_comment = true;
        }
        // Keep CR so CRLF lines still end where they did; everything else in a comment becomes a blank.
        if (in_comment && c != '\r') c = ' ';
    }
    return out;
}

bool iequals(std::string_view a, std::string_view b) noexcept {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        char x = a[i], y = b[i];
        if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
        if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
        if (x != y) return false;
    }
    return true;
}

}  // namespace mocapdb::detail
