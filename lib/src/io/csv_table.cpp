#include "mocapdb/io/csv_table.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/text_file.hpp"

namespace mocapdb {
namespace {

struct Row {
    std::size_t line = 0;
    std::vector<std::string> cells;
    std::vector<std::size_t> columns;  // 1-based column of each cell's start
};

// RFC 4180 rows; quoted cells may hold commas, quotes ("") and line breaks. Blank rows are dropped.
std::vector<Row> split_rows(std::string_view text, const std::string& source) {
    std::vector<Row> rows;
    std::size_t i = 0, line = 1, line_start = 0;
    if (text.substr(0, 3) == "\xEF\xBB\xBF") i = line_start = 3;  // UTF-8 byte order mark
    while (i < text.size()) {
        Row row;
        row.line = line;
        for (;;) {
            std::string cell;
            row.columns.push_back(i - line_start + 1);
            std::size_t j = i;  // spaces before an opening quote are allowed
            while (j < text.size() && (text[j] == ' ' || text[j] == '\t')) ++j;
            if (j < text.size() && text[j] == '"') {
                i = j;
                const std::size_t open_line = line, open_col = i - line_start + 1;
                ++i;
                for (;;) {
                    if (i >= text.size())
                        throw ParseError(source, open_line, open_col,
                                         "unterminated quoted field (expected a closing quote)");
                    if (text[i] == '"') {
                        if (i + 1 < text.size() && text[i + 1] == '"') {
                            cell += '"';
                            i += 2;
                            continue;
                        }
                        ++i;
                        break;
                    }
                    if (text[i] == '\n') {
                        ++line;
                        line_start = i + 1;
                    }
                    cell += text[i++];
                }
                while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
                if (i < text.size() && text[i] != ',' && text[i] != '\n' && text[i] != '\r')
                    throw ParseError(source, line, i - line_start + 1,
                                     "expected ',' or end of line after a quoted field");
            } else {
                while (i < text.size() && text[i] != ',' && text[i] != '\n' && text[i] != '\r') cell += text[i++];
            }
            row.cells.push_back(trim_blanks(cell));
            if (i < text.size() && text[i] == ',') {
                ++i;
                continue;
            }
            break;
        }
        if (i < text.size() && text[i] == '\r') ++i;
        if (i < text.size() && text[i] == '\n') ++i;
        ++line;
        line_start = i;
        const bool blank = row.cells.size() == 1 && row.cells[0].empty();
        if (!blank) rows.push_back(std::move(row));
    }
    return rows;
}

}  // namespace

std::string trim_blanks(std::string_view text) {
    const auto b = text.find_first_not_of(" \t");
    if (b == std::string_view::npos) return "";
    const auto e = text.find_last_not_of(" \t");
    return std::string(text.substr(b, e - b + 1));
}

CsvTable CsvTable::read(const std::filesystem::path& file) { return parse(read_text_file(file), file.string()); }

CsvTable CsvTable::parse(std::string_view text, const std::string& source) {
    std::vector<Row> rows = split_rows(text, source);
    if (rows.empty()) throw ParseError(source, 1, 0, "expected a header row with column names, found an empty file");
    CsvTable t;
    t.file = source;
    t.header = std::move(rows.front().cells);
    t.header_line = rows.front().line;
    t.header_columns = std::move(rows.front().columns);
    for (std::size_t r = 1; r < rows.size(); ++r) {
        if (rows[r].cells.size() != t.header.size())
            throw ParseError(source, rows[r].line, 0,
                             "expected " + std::to_string(t.header.size()) +
                                 " comma-separated cells (as in the header), found " +
                                 std::to_string(rows[r].cells.size()));
        t.cells.push_back(std::move(rows[r].cells));
        t.line_of_row.push_back(rows[r].line);
        t.column_of_cell.push_back(std::move(rows[r].columns));
    }
    return t;
}

void CsvTable::require_data_rows() const {
    if (cells.empty())
        throw ParseError(file, header_line + 1, 0, "expected at least one data row after the header, found none");
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
        throw ParseError(file, header_line, 0, "expected a column named '" + name + "', found columns: " + list);
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
                throw ParseError(file, line_of_row[r], column_of_cell[r][idx[c]],
                                 "field " + std::to_string(idx[c] + 1) + " (column '" + names[c] +
                                     "'): expected a finite number, found '" + cell + "'");
            }
            m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = v;
        }
    }
    return m;
}

}  // namespace mocapdb
