#include "option_lists.hpp"

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/csv_table.hpp"

namespace mocapdb::cli {
std::vector<std::string> split_names(const std::string& list, const std::string& option) {
    std::vector<std::string> out;
    std::string cur;
    for (char ch : list + ",") {
        if (ch == ',') {
            const std::string t = trim_blanks(cur);
            if (t.empty())
                throw InvalidArgument(option + ": expected comma-separated column names, found '" + list + "'");
            out.push_back(t);
            cur.clear();
        } else {
            cur.push_back(ch);
        }
    }
    return out;
}

}  // namespace mocapdb::cli
