#pragma once
// The R-written reference CSVs of the kriging tests (header row, quoted strings, numbers), read by the
// library's CsvTable, with lookups by column name.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mocapdb/io/csv_table.hpp"

namespace mocapdb::test {

struct CsvTable {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;

    std::size_t column(const std::string& name) const {
        for (std::size_t k = 0; k < header.size(); ++k) {
            if (header[k] == name) return k;
        }
        throw std::runtime_error("csv: no column " + name);
    }
    std::string text(std::size_t row, const std::string& name) const { return rows.at(row).at(column(name)); }
    double number(std::size_t row, const std::string& name) const {
        return std::strtod(text(row, name).c_str(), nullptr);
    }
    /// Rows whose column `key` equals `value` (all rows when key is empty).
    std::vector<std::size_t> select(const std::string& key, const std::string& value) const {
        std::vector<std::size_t> out;
        for (std::size_t r = 0; r < rows.size(); ++r) {
            if (key.empty() || text(r, key) == value) out.push_back(r);
        }
        return out;
    }
    Eigen::MatrixXd matrix(const std::vector<std::string>& names, const std::vector<std::size_t>& which) const {
        Eigen::MatrixXd m(static_cast<Eigen::Index>(which.size()), static_cast<Eigen::Index>(names.size()));
        for (std::size_t r = 0; r < which.size(); ++r) {
            for (std::size_t c = 0; c < names.size(); ++c) {
                m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = number(which[r], names[c]);
            }
        }
        return m;
    }
    Eigen::MatrixXd matrix(const std::vector<std::string>& names) const { return matrix(names, select("", "")); }
};

inline CsvTable read_csv(const std::filesystem::path& path) {
    const mocapdb::CsvTable csv = mocapdb::CsvTable::read(path);
    return CsvTable{csv.header, csv.cells};
}

inline double rel_err(double a, double b) {
    const double d = std::abs(a - b);
    const double s = std::max(std::abs(b), 1e-300);
    return d / s;
}

}  // namespace mocapdb::test
