#pragma once
// Reader for plain numeric tables (CSV with a header row), used by the kriging commands so that the
// engine can be run on the same files as any geostatistics package. Cells may be quoted; every data
// cell of a selected column must be a finite number. Errors are ParseError("FILE:LINE:COLUMN: ...")
// naming what was expected and what was found, or IoError when the file cannot be read.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace mocapdb::cli {

struct NumericCsv {
    std::string file;
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> cells;  ///< raw data cells, one vector per data row
    std::vector<std::size_t> line_of_row;         ///< 1-based line number of each data row

    /// Reads FILE. Throws IoError / ParseError (empty file, ragged rows).
    static NumericCsv read(const std::string& file);

    /// Columns by name as an R by names.size() matrix. Throws ParseError naming the file, line and
    /// column of the first cell that is not a finite number, or the missing column name.
    Eigen::MatrixXd columns(const std::vector<std::string>& names) const;
};

/// Splits "x,y,z" into {"x","y","z"} (whitespace trimmed; empty names rejected with InvalidArgument).
std::vector<std::string> split_names(const std::string& list, const std::string& option);

}  // namespace mocapdb::cli
