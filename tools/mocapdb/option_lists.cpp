#include "option_lists.hpp"

#include "mocapdb/core/error.hpp"

namespace mocapdb::cli {
namespace {

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t");
    return s.substr(b, e - b + 1);
}

}  // namespace

std::vector<std::string> split_names(const std::string& list, const std::string& option) {
    std::vector<std::string> out;
    std::string cur;
    for (char ch : list + ",") {
        if (ch == ',') {
            const std::string t = trim(cur);
            if (t.empty()) throw InvalidArgument(option + ": expected comma-separated column names, found '" + list + "'");
            out.push_back(t);
            cur.clear();
        } else {
            cur.push_back(ch);
        }
    }
    return out;
}

}  // namespace mocapdb::cli
