#include "mocapdb/io/csv_table.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/text_file.hpp"

namespace mocapdb {
namespace {

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t");
    return s.substr(b, e - b + 1);
}

// Splits one line; quoted cells may contain commas; "" inside quotes is a quote.
std::vector<std::string> split_line(std::string_view line, const std::string& file, std::size_t lineno) {
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
    if (quoted) throw ParseError(file, lineno, line.size(), "unterminated quoted cell (expected a closing quote before the end of the line)");
    out.push_back(trim(cur));
    return out;
}

}  // namespace

CsvTable CsvTable::read(const std::filesystem::path& file) { return parse(read_text_file(file), file.string()); }

CsvTable CsvTable::parse(std::string_view text, const std::string& source) {
    CsvTable t;
    t.file = source;
    std::size_t lineno = 0, start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(start, end - start);
        start = end + 1;
        ++lineno;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (trim(std::string(line)).empty()) continue;
        std::vector<std::string> cells = split_line(line, source, lineno);
        if (t.header.empty()) {
            t.header = std::move(cells);
            continue;
        }
        if (cells.size() != t.header.size())
            throw ParseError(source, lineno, 0,
                             "expected " + std::to_string(t.header.size()) + " comma-separated cells (as in the header), found " +
                                 std::to_string(cells.size()));
        t.cells.push_back(std::move(cells));
        t.line_of_row.push_back(lineno);
    }
    if (t.header.empty()) throw ParseError(source, 1, 0, "expected a header row with column names, found an empty file");
    if (t.cells.empty()) throw ParseError(source, lineno + 1, 0, "expected at least one data row after the header, found none");
    return t;
}

long CsvTable::find_column(const std::string& name) const {
    for (std::size_t k = 0; k < header.size(); ++k)
        if (header[k] == name) return static_cast<long>(k);
    return -1;
}

std::size_t CsvTable::column(const std::string& name) const {
    const long k = find_column(name);
    if (k < 0) {
        std::string list;
        for (const auto& h : header) list += (list.empty() ? "" : ", ") + h;
        throw ParseError(file, 1, 0, "expected a column named '" + name + "', found columns: " + list);
    }
    return static_cast<std::size_t>(k);
}

Eigen::MatrixXd CsvTable::columns(const std::vector<std::string>& names) const {
    std::vector<std::size_t> idx;
    for (const auto& name : names) idx.push_back(column(name));
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

}  // namespace mocapdb
