#pragma once
// The one CSV reader of mocapdb: a header row of column names, then data rows, every row
// with the header's number of comma-separated cells. Cells may be quoted (RFC 4180: commas, quotes as
// "" and line breaks inside quotes); blank lines are skipped; cells are trimmed of spaces and tabs;
// CRLF line ends and a UTF-8 byte order mark are accepted. Used for control parameters, the kriging
// commands' tables, the import manifest, the ACL reference and the tests' reference tables.
//
// Errors: IoError when the file cannot be read; ParseError("FILE:LINE:COLUMN: ...") naming what was
// expected and what was found (no header, a ragged row, an unterminated quote, a missing column, a
// cell that is not a finite number; no data row where require_data_rows is called). Thread safety:
// plain data.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace mocapdb {

struct CsvTable {
    std::string file;                                      ///< the name errors give
    std::vector<std::string> header;                       ///< column names
    std::vector<std::vector<std::string>> cells;           ///< data cells, one vector per data row
    std::vector<std::size_t> line_of_row;                  ///< 1-based line number of each data row
    std::vector<std::vector<std::size_t>> column_of_cell;  ///< 1-based column where each data cell starts
    std::size_t header_line = 1;                           ///< 1-based line of the header
    std::vector<std::size_t> header_columns;               ///< 1-based column where each name starts

    /// Reads and parses a file.
    static CsvTable read(const std::filesystem::path& file);
    /// Parses text; `source` names it in errors.
    static CsvTable parse(std::string_view text, const std::string& source);
    /// ParseError unless there is at least one data row.
    void require_data_rows() const;

    /// Index of a column, or -1.
    long find_column(const std::string& name) const;
    /// Index of a column; ParseError listing the columns when there is none.
    std::size_t column(const std::string& name) const;
    /// Columns by name as an R by names.size() matrix of finite numbers (ParseError at the first cell
    /// that is not one, naming its line and column).
    Eigen::MatrixXd columns(const std::vector<std::string>& names) const;
};

/// `text` without the spaces and tabs at its ends (how CSV cells and comma-separated lists are trimmed).
std::string trim_blanks(std::string_view text);

}  // namespace mocapdb
