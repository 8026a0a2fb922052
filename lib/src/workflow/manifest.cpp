// The import manifest CSV (format in mocapdb/workflow/manifest.hpp).
#include "mocapdb/workflow/manifest.hpp"

#include <charconv>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/csv_table.hpp"
#include "mocapdb/io/text_file.hpp"

namespace mocapdb::workflow {

Manifest Manifest::parse(std::string_view text, const std::string& source_name) {
    if (text.find_first_not_of(" \t\r\n") == std::string_view::npos)
        throw ParseError(source_name, 1, 0, "empty manifest (expected a header row with a 'file' column)");
    const CsvTable csv = CsvTable::parse(text, source_name);
    enum Column { File, Subject, Description, Labels, Fps };
    std::vector<Column> columns;
    int file_column = -1;
    for (std::size_t c = 0; c < csv.header.size(); ++c) {
        const std::string& name = csv.header[c];
        Column col;
        if (name == "file") {
            col = File;
            file_column = static_cast<int>(c);
        } else if (name == "subject") {
            col = Subject;
        } else if (name == "description") {
            col = Description;
        } else if (name == "labels") {
            col = Labels;
        } else if (name == "fps") {
            col = Fps;
        } else {
            throw ParseError(
                source_name, csv.header_line, csv.header_columns[c],
                "unknown manifest column '" + name + "' (expected file, subject, description, labels, fps)");
        }
        for (const Column seen : columns)
            if (seen == col)
                throw ParseError(source_name, csv.header_line, csv.header_columns[c],
                                 "column '" + name + "' appears twice");
        columns.push_back(col);
    }
    if (file_column < 0) throw ParseError(source_name, csv.header_line, 1, "the header has no 'file' column");

    Manifest m;
    std::unordered_map<std::string, std::size_t> first_line;
    for (std::size_t r = 0; r < csv.cells.size(); ++r) {
        const std::vector<std::string>& fields = csv.cells[r];
        const std::size_t line = csv.line_of_row[r];
        const std::vector<std::size_t>& at = csv.column_of_cell[r];
        ManifestEntry e;
        std::string file;
        for (std::size_t c = 0; c < columns.size(); ++c) {
            const std::string& value = fields[c];
            switch (columns[c]) {
                case File: file = value; break;
                case Subject: e.subject = value; break;
                case Description: e.description = value; break;
                case Labels: {
                    std::size_t start = 0;
                    while (start <= value.size()) {
                        std::size_t end = value.find(';', start);
                        if (end == std::string::npos) end = value.size();
                        const std::string label = trim_blanks(value.substr(start, end - start));
                        if (!label.empty()) e.labels.push_back(label);
                        start = end + 1;
                    }
                    break;
                }
                case Fps: {
                    if (value.empty()) break;
                    double fps = 0.0;
                    const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), fps);
                    if (ec != std::errc() || ptr != value.data() + value.size() || !(fps > 0.0) || !std::isfinite(fps))
                        throw ParseError(source_name, line, at[c],
                                         "expected a positive frame rate in Hz, found '" + value + "'");
                    e.frame_rate = fps;
                    break;
                }
            }
        }
        if (file.empty())
            throw ParseError(source_name, line, at[static_cast<std::size_t>(file_column)], "empty 'file' field");
        if (const auto it = first_line.find(file); it != first_line.end())
            throw ParseError(source_name, line, at[static_cast<std::size_t>(file_column)],
                             "file '" + file + "' is listed twice (first on line " + std::to_string(it->second) + ")");
        first_line.emplace(file, line);
        m.entries_.emplace(file, std::move(e));
    }
    return m;
}

Manifest Manifest::read(const std::filesystem::path& path) { return parse(read_text_file(path), path.string()); }

const ManifestEntry* Manifest::find(const std::filesystem::path& source) const {
    if (const auto it = entries_.find(source.filename().string()); it != entries_.end()) return &it->second;
    if (const auto it = entries_.find(source.stem().string()); it != entries_.end()) return &it->second;
    return nullptr;
}

}  // namespace mocapdb::workflow
