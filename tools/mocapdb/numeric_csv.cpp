#include "numeric_csv.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "mocapdb/core/error.hpp"

namespace mocapdb::cli {
namespace {

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t");
    return s.substr(b, e - b + 1);
}

// Splits one CSV line; quoted cells may contain commas; "" inside quotes is a quote.
std::vector<std::string> split_line(const std::string& line, const std::string& file, std::size_t lineno) {
    std::vector<std::string> out;
    std::string cur;
    bool quoted = false;
    for (std::size_t k = 0; k < line.size(); ++k) {
        const char ch = line[k];
        if (quoted) {
            if (ch == '"') {
                if (k + 1 < line.size() && line[k + 1] == '"') {
                    cur.push_back('"');
                    ++k;
                } else {
                    quoted = false;
                }
            } else {
                cur.push_back(ch);
            }
        } else if (ch == '"') {
            quoted = true;
        } else if (ch == ',') {
            out.push_back(trim(cur));
            cur.clear();
        } else {
            cur.push_back(ch);
        }
    }
    if (quoted) throw ParseError(file, lineno, line.size(), "unterminated quoted cell");
    out.push_back(trim(cur));
    return out;
}

}  // namespace

NumericCsv NumericCsv::read(const std::string& file) {
    std::ifstream in(file);
    if (!in) throw IoError(file + ": cannot open: " + std::strerror(errno));
    NumericCsv t;
    t.file = file;
    std::string line;
    std::size_t lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (trim(line).empty()) continue;
        std::vector<std::string> cells = split_line(line, file, lineno);
        if (t.header.empty()) {
            t.header = std::move(cells);
            continue;
        }
        if (cells.size() != t.header.size()) {
            throw ParseError(file, lineno, 0,
                             "expected " + std::to_string(t.header.size()) + " comma-separated fields (as in the header), found " +
                                 std::to_string(cells.size()));
        }
        t.cells.push_back(std::move(cells));
        t.line_of_row.push_back(lineno);
    }
    if (t.header.empty()) throw ParseError(file, 1, 0, "expected a header row with column names, found an empty file");
    if (t.cells.empty()) throw ParseError(file, lineno + 1, 0, "expected at least one data row after the header, found none");
    return t;
}

Eigen::MatrixXd NumericCsv::columns(const std::vector<std::string>& names) const {
    std::vector<std::size_t> idx;
    for (const auto& name : names) {
        std::size_t k = 0;
        while (k < header.size() && header[k] != name) ++k;
        if (k == header.size()) {
            std::string list;
            for (const auto& h : header) list += (list.empty() ? "" : ", ") + h;
            throw ParseError(file, 1, 0, "expected a column named '" + name + "', found columns: " + list);
        }
        idx.push_back(k);
    }
    Eigen::MatrixXd m(static_cast<Eigen::Index>(cells.size()), static_cast<Eigen::Index>(names.size()));
    for (std::size_t r = 0; r < cells.size(); ++r) {
        for (std::size_t c = 0; c < idx.size(); ++c) {
            const std::string& cell = cells[r][idx[c]];
            char* end = nullptr;
            errno = 0;
            const double v = std::strtod(cell.c_str(), &end);
            if (cell.empty() || end != cell.c_str() + cell.size() || !std::isfinite(v)) {
                throw ParseError(file, line_of_row[r], 0,
                                 "field " + std::to_string(idx[c] + 1) + " (column '" + names[c] +
                                     "'): expected a finite number, found '" + cell + "'");
            }
            m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = v;
        }
    }
    return m;
}

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
