#include "mocapdb/eval/acl_reference.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/csv_table.hpp"

namespace mocapdb::eval {
namespace {

const char* const kRequired[] = {"clip",   "precision_cm", "status", "joints", "end_sites",
                                 "frames", "acl_bytes",    "max_cm", "rmse_cm"};

std::string shown(const std::string& cell) { return cell.empty() ? "an empty cell" : "'" + cell + "'"; }

double real_cell(const std::string& file, std::size_t line, std::size_t column, const std::string& name,
                 const std::string& cell) {
    errno = 0;
    char* end = nullptr;
    const double v = cell.empty() ? 0.0 : std::strtod(cell.c_str(), &end);
    if (cell.empty() || end != cell.c_str() + cell.size() || errno == ERANGE || !std::isfinite(v) || v < 0.0)
        throw ParseError(file, line, column, "column '" + name + "': expected a number >= 0, found " + shown(cell));
    return v;
}

std::uint64_t whole_cell(const std::string& file, std::size_t line, std::size_t column, const std::string& name,
                         const std::string& cell) {
    const bool digits =
        !cell.empty() && std::all_of(cell.begin(), cell.end(), [](char c) { return c >= '0' && c <= '9'; });
    errno = 0;
    const unsigned long long v = digits ? std::strtoull(cell.c_str(), nullptr, 10) : 0;
    if (!digits || errno == ERANGE)
        throw ParseError(file, line, column, "column '" + name + "': expected a whole number, found " + shown(cell));
    return static_cast<std::uint64_t>(v);
}

}  // namespace

AclTable read_acl_table(const std::filesystem::path& path) {
    const std::string file = path.string();
    const CsvTable csv = CsvTable::read(path);
    csv.require_data_rows();
    AclTable table;
    table.files.push_back(path);
    std::map<std::string, std::size_t> column;
    for (std::size_t i = 0; i < csv.header.size(); ++i) column.emplace(csv.header[i], i);
    for (const char* name : kRequired)
        if (!column.count(name))
            throw ParseError(file, 1, 0,
                             std::string("expected a header naming column '") + name +
                                 "' (a per-clip ACL table: clip, precision_cm, status, joints, end_sites, "
                                 "frames, acl_bytes, max_cm, rmse_cm, ...)");
    for (std::size_t row = 0; row < csv.cells.size(); ++row) {
        const std::vector<std::string>& cells = csv.cells[row];
        const std::size_t line_no = csv.line_of_row[row];
        auto cell = [&](const char* name) -> const std::string& { return cells[column.at(name)]; };
        auto col = [&](const char* name) { return column.at(name) + 1; };
        if (cell("status") != "ok" || cell("precision_cm") == "raw") {
            ++table.skipped_rows;
            continue;
        }
        AclClipRow r;
        r.line = line_no;
        r.clip = cell("clip");
        if (r.clip.empty())
            throw ParseError(file, line_no, col("clip"), "column 'clip': expected a clip name, found an empty cell");
        if (column.count("dataset")) r.dataset = cell("dataset");
        r.precision_cm = real_cell(file, line_no, col("precision_cm"), "precision_cm", cell("precision_cm"));
        if (!(r.precision_cm > 0.0))
            throw ParseError(
                file, line_no, col("precision_cm"),
                "column 'precision_cm': expected a precision > 0 or 'raw', found '" + cell("precision_cm") + "'");
        r.joints = static_cast<std::size_t>(whole_cell(file, line_no, col("joints"), "joints", cell("joints")));
        r.end_sites =
            static_cast<std::size_t>(whole_cell(file, line_no, col("end_sites"), "end_sites", cell("end_sites")));
        r.frames = static_cast<std::size_t>(whole_cell(file, line_no, col("frames"), "frames", cell("frames")));
        r.acl_bytes = whole_cell(file, line_no, col("acl_bytes"), "acl_bytes", cell("acl_bytes"));
        r.max_cm = real_cell(file, line_no, col("max_cm"), "max_cm", cell("max_cm"));
        r.rmse_cm = real_cell(file, line_no, col("rmse_cm"), "rmse_cm", cell("rmse_cm"));
        if (r.frames == 0 || r.joints + r.end_sites == 0)
            throw ParseError(file, line_no, 0,
                             "expected frames > 0 and joints + end_sites > 0 (the RMSE's weight), found " +
                                 std::to_string(r.frames) + " frames, " + std::to_string(r.joints + r.end_sites) +
                                 " positions per frame");
        table.rows.push_back(std::move(r));
    }
    return table;
}

void append(AclTable& table, AclTable more) {
    table.files.insert(table.files.end(), more.files.begin(), more.files.end());
    table.rows.insert(table.rows.end(), std::make_move_iterator(more.rows.begin()),
                      std::make_move_iterator(more.rows.end()));
    table.skipped_rows += more.skipped_rows;
}

bool AclCollection::complete() const {
    if (!missing.empty() || settings.empty()) return false;
    return std::all_of(settings.begin(), settings.end(), [&](const AclSetting& s) { return s.clips == requested; });
}

AclCollection aggregate_acl(const AclTable& table, const std::vector<std::string>& clips) {
    const std::set<std::string> wanted(clips.begin(), clips.end());
    struct Sum {
        std::uint64_t bytes = 0;
        double max = 0.0, sq = 0.0, n = 0.0;
        std::size_t clips = 0;
    };
    std::map<double, Sum> per;
    std::set<std::string> seen;
    for (const AclClipRow& r : table.rows) {
        if (!wanted.empty() && !wanted.count(r.clip)) continue;
        seen.insert(r.clip);
        Sum& s = per[r.precision_cm];
        const double n = static_cast<double>(r.frames) * static_cast<double>(r.joints + r.end_sites);
        ++s.clips;
        s.bytes += r.acl_bytes;
        s.max = std::max(s.max, r.max_cm);
        s.sq += r.rmse_cm * r.rmse_cm * n;
        s.n += n;
    }
    AclCollection out;
    out.requested = wanted.empty() ? seen.size() : wanted.size();
    for (const std::string& c : wanted)
        if (!seen.count(c)) out.missing.push_back(c);
    for (const auto& [precision, s] : per)
        out.settings.push_back({precision, s.bytes, s.max, std::sqrt(s.sq / s.n), s.clips});
    return out;
}

std::optional<double> bytes_at_error(std::vector<std::pair<double, double>> points, double error) {
    if (points.empty() || !(error > 0.0)) return std::nullopt;
    std::sort(points.begin(), points.end());
    if (error < points.front().first || error > points.back().first) return std::nullopt;
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        const auto [e0, b0] = points[i];
        const auto [e1, b1] = points[i + 1];
        if (e0 <= error && error <= e1) {
            const double t = e1 == e0 ? 0.0 : (std::log(error) - std::log(e0)) / (std::log(e1) - std::log(e0));
            return std::exp(std::log(b0) + t * (std::log(b1) - std::log(b0)));
        }
    }
    return std::nullopt;  // a single point that is not `error` itself (compare.py: the same)
}

AclComparison compare_with_acl(const AclCollection& acl, double bytes, double max_cm, double rmse_cm) {
    std::vector<std::pair<double, double>> at_max, at_rmse;
    for (const AclSetting& s : acl.settings) {
        at_max.emplace_back(s.max_cm, static_cast<double>(s.bytes));
        at_rmse.emplace_back(s.rmse_cm, static_cast<double>(s.bytes));
    }
    // Below the most precise setting's error: its bytes, a lower bound when it is the largest.
    auto below_range = [](const std::vector<std::pair<double, double>>& points, double error, bool& bound) {
        std::optional<double> out = bytes_at_error(points, error);
        if (out || points.empty() || !(error > 0.0)) return out;
        const auto finest = std::min_element(points.begin(), points.end());
        const bool largest = std::all_of(points.begin(), points.end(), [&](const std::pair<double, double>& p) {
            return p.second <= finest->second;
        });
        if (error < finest->first && largest) {
            bound = true;
            out = finest->second;
        }
        return out;
    };
    AclComparison c;
    c.bytes_at_max = below_range(at_max, max_cm, c.max_lower_bound);
    c.bytes_at_rmse = below_range(at_rmse, rmse_cm, c.rmse_lower_bound);
    if (bytes > 0.0) {
        if (c.bytes_at_max) c.smaller_at_max = *c.bytes_at_max / bytes;
        if (c.bytes_at_rmse) c.smaller_at_rmse = *c.bytes_at_rmse / bytes;
    }
    return c;
}

}  // namespace mocapdb::eval
