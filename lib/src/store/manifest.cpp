// The import manifest CSV (format in mocapdb/store/manifest.hpp).
#include "mocapdb/store/manifest.hpp"

#include <charconv>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/text_file.hpp"

namespace mocapdb {
namespace {

struct Row {
    std::size_t line = 0;
    std::vector<std::string> fields;
    std::vector<std::size_t> columns;  // 1-based column of each field's start
};

// RFC 4180 fields; quoted fields may hold commas, quotes ("") and line breaks.
std::vector<Row> split_csv(std::string_view text, const std::string& source) {
    std::vector<Row> rows;
    std::size_t i = 0, line = 1, line_start = 0;
    if (text.substr(0, 3) == "\xEF\xBB\xBF") i = line_start = 3;  // UTF-8 byte order mark
    while (i < text.size()) {
        Row row;
        row.line = line;
        for (;;) {
            std::string field;
            row.columns.push_back(i - line_start + 1);
            if (i < text.size() && text[i] == '"') {
                const std::size_t open_line = line, open_col = i - line_start + 1;
                ++i;
                for (;;) {
                    if (i >= text.size()) throw ParseError(source, open_line, open_col, "unterminated quoted field");
                    if (text[i] == '"') {
                        if (i + 1 < text.size() && text[i + 1] == '"') {
                            field += '"';
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
                    field += text[i++];
                }
                if (i < text.size() && text[i] != ',' && text[i] != '\n' && text[i] != '\r')
                    throw ParseError(source, line, i - line_start + 1, "expected ',' or end of line after a quoted field");
            } else {
                while (i < text.size() && text[i] != ',' && text[i] != '\n' && text[i] != '\r') field += text[i++];
            }
            row.fields.push_back(std::move(field));
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
        const bool blank = row.fields.size() == 1 && row.fields[0].find_first_not_of(" \t") == std::string::npos;
        if (!blank) rows.push_back(std::move(row));
    }
    return rows;
}

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t");
    return s.substr(b, e - b + 1);
}

}  // namespace

Manifest Manifest::parse(std::string_view text, const std::string& source_name) {
    const std::vector<Row> rows = split_csv(text, source_name);
    if (rows.empty()) throw ParseError(source_name, 1, 0, "empty manifest (expected a header row with a 'file' column)");
    enum Column { File, Subject, Description, Labels, Fps };
    std::vector<Column> columns;
    int file_column = -1;
    const Row& header = rows.front();
    for (std::size_t c = 0; c < header.fields.size(); ++c) {
        const std::string name = trim(header.fields[c]);
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
            throw ParseError(source_name, header.line, header.columns[c],
                             "unknown manifest column '" + name + "' (expected file, subject, description, labels, fps)");
        }
        for (const Column seen : columns)
            if (seen == col) throw ParseError(source_name, header.line, header.columns[c], "column '" + name + "' appears twice");
        columns.push_back(col);
    }
    if (file_column < 0) throw ParseError(source_name, header.line, 1, "the header has no 'file' column");

    Manifest m;
    std::unordered_map<std::string, std::size_t> first_line;
    for (std::size_t r = 1; r < rows.size(); ++r) {
        const Row& row = rows[r];
        if (row.fields.size() != columns.size())
            throw ParseError(source_name, row.line, 0,
                             "expected " + std::to_string(columns.size()) + " fields (as in the header), found " +
                                 std::to_string(row.fields.size()));
        ManifestEntry e;
        std::string file;
        for (std::size_t c = 0; c < columns.size(); ++c) {
            const std::string value = trim(row.fields[c]);
            switch (columns[c]) {
                case File: file = value; break;
                case Subject: e.subject = value; break;
                case Description: e.description = value; break;
                case Labels: {
                    std::size_t start = 0;
                    while (start <= value.size()) {
                        std::size_t end = value.find(';', start);
                        if (end == std::string::npos) end = value.size();
                        const std::string label = trim(value.substr(start, end - start));
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
                        throw ParseError(source_name, row.line, row.columns[c],
                                         "expected a positive frame rate in Hz, found '" + value + "'");
                    e.frame_rate = fps;
                    break;
                }
            }
        }
        if (file.empty()) throw ParseError(source_name, row.line, row.columns[static_cast<std::size_t>(file_column)], "empty 'file' field");
        if (const auto it = first_line.find(file); it != first_line.end())
            throw ParseError(source_name, row.line, row.columns[static_cast<std::size_t>(file_column)],
                             "file '" + file + "' is listed twice (first on line " + std::to_string(it->second) + ")");
        first_line.emplace(file, row.line);
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

}  // namespace mocapdb
