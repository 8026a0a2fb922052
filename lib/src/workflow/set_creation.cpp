#include "mocapdb/workflow/set_creation.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/io/csv_table.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::workflow {
namespace {

// Splits "NAME[UNIT]" into name and unit.
std::pair<std::string, std::string> name_and_unit(const std::string& header) {
    const auto open = header.find('[');
    if (open == std::string::npos || header.back() != ']') return {header, ""};
    return {header.substr(0, open), header.substr(open + 1, header.size() - open - 2)};
}

// Appends a numeric parameter column (the set's periods and levels, when kept, get a linear entry).
void append_numeric_parameter(MotionSet& set, const std::string& name, const std::string& unit, const VecX& column) {
    const Eigen::Index p = set.parameters.cols();
    set.parameters.conservativeResize(column.size(), p + 1);
    set.parameters.col(p) = column;
    set.parameter_names.push_back(name);
    set.parameter_units.push_back(unit);
    if (set.parameter_periods.size() != 0) {
        set.parameter_periods.conservativeResize(p + 1);
        set.parameter_periods(p) = 0.0;
    }
    if (!set.parameter_levels.empty()) set.parameter_levels.emplace_back();
}

bool is_number(const std::string& cell) {
    char* end = nullptr;
    const double v = std::strtod(cell.c_str(), &end);
    return !cell.empty() && end == cell.c_str() + cell.size() && std::isfinite(v);
}

// Appends the CSV's parameters to the set's (after any extracted ones): first column the sample label,
// then one column per parameter, headers "name" or "name[unit]". A column of numbers is numeric; a
// column without any number is categorical (its cells are the levels); a mix is refused.
void apply_params_csv(MotionSet& set, const std::filesystem::path& path, const Database& db) {
    const std::string file = path.string();
    const CsvTable csv = CsvTable::read(path);
    csv.require_data_rows();
    if (csv.header.size() < 2)
        throw ParseError(file, 1, 0, "expected a header 'sample,p1[,p2...]' with at least one parameter column");
    std::map<std::string, std::size_t> row_of;
    for (std::size_t r = 0; r < csv.cells.size(); ++r) {
        if (!row_of.emplace(csv.cells[r][0], r).second)
            throw ParseError(file, csv.line_of_row[r], 1, "sample '" + csv.cells[r][0] + "' appears twice");
    }
    std::vector<std::size_t> rows;  // the CSV row of each sample
    for (const SampleRef& s : set.samples) {
        const std::string label = sample_label(s, db.find_clip(s.clip)->frames);
        auto it = row_of.find(label);
        if (it == row_of.end())
            throw ParseError(
                file, 0, 0,
                "no row for sample '" + label + "' (first column: sample labels as 'CLIP' or 'CLIP:BEGIN-END')");
        rows.push_back(it->second);
    }
    if (set.parameters.rows() != static_cast<Eigen::Index>(rows.size()))
        set.parameters.resize(static_cast<Eigen::Index>(rows.size()), 0);
    for (std::size_t c = 1; c < csv.header.size(); ++c) {
        const auto [name, unit] = name_and_unit(csv.header[c]);
        const std::size_t header_column = c < csv.header_columns.size() ? csv.header_columns[c] : 0;
        if (std::find(set.parameter_names.begin(), set.parameter_names.end(), name) != set.parameter_names.end())
            throw ParseError(file, csv.header_line, header_column,
                             "parameter '" + name + "' is given twice (also measured, or a repeated column)");
        std::size_t numbers = 0, first_text = 0, first_number = 0;
        for (std::size_t r = csv.cells.size(); r-- > 0;) {
            if (is_number(csv.cells[r][c])) {
                ++numbers;
                first_number = r;
            } else {
                first_text = r;
            }
        }
        if (numbers == csv.cells.size()) {
            VecX column(static_cast<Eigen::Index>(rows.size()));
            for (std::size_t i = 0; i < rows.size(); ++i)
                column(static_cast<Eigen::Index>(i)) = std::strtod(csv.cells[rows[i]][c].c_str(), nullptr);
            append_numeric_parameter(set, name, unit, column);
            continue;
        }
        if (numbers > 0)
            throw ParseError(file, csv.line_of_row[first_text], csv.column_of_cell[first_text][c],
                             "column '" + csv.header[c] + "' mixes numbers (line " +
                                 std::to_string(csv.line_of_row[first_number]) + ") and text ('" +
                                 csv.cells[first_text][c] +
                                 "'): a numeric parameter needs finite numbers, a categorical one level names");
        if (!unit.empty())
            throw ParseError(file, csv.header_line, header_column,
                             "column '" + csv.header[c] + "' holds level names (a categorical parameter): no unit");
        for (std::size_t r = 0; r < csv.cells.size(); ++r)
            if (csv.cells[r][c].empty())
                throw ParseError(file, csv.line_of_row[r], csv.column_of_cell[r][c],
                                 "column '" + name + "' (categorical): empty level name");
        std::vector<std::string> levels;
        for (const std::size_t r : rows) levels.push_back(csv.cells[r][c]);
        add_categorical_parameter(set, name, levels);
    }
    const std::string source = "csv:" + std::filesystem::path(file).filename().string();
    set.parameter_source += (set.parameter_source.empty() ? "" : "; ") + source;
}

}  // namespace

std::vector<std::string> select_clips(const Database& db, const std::string& db_name,
                                      const std::vector<std::string>& patterns) {
    const auto records = db.clips();
    std::vector<std::string> out;
    std::set<std::string> seen;
    for (const std::string& pattern : patterns) {
        bool matched = false;
        for (const ClipRecord& r : records) {
            if (fnmatch(pattern.c_str(), r.id.c_str(), 0) != 0) continue;
            matched = true;
            if (seen.insert(r.id).second) out.push_back(r.id);
        }
        if (!matched)
            throw InvalidArgument(db_name + ": no clip matches '" + pattern + "' (mocapdb info " + db_name +
                                  " lists them)");
    }
    return out;
}

SetOutcome create_set(const std::filesystem::path& db_file, const SetRequest& a) {
    const std::string db_path = db_file.string();
    DatabaseWriter writer(db_path, DatabaseWriter::Mode::OpenOrCreate);
    const Database& db = writer.view();
    if (db.clips().empty()) throw InvalidArgument(db_path + ": the database holds no clips; import some first");
    if (db.has_set(a.name) && !a.replace)
        throw Refused<InvalidArgument>(Remedy::Overwrite, db_path + ": set '" + a.name + "' exists");
    SetOutcome o;
    SetBuildOptions options;
    options.name = a.name;
    parse_segmentation(a.segment, options);
    o.auto_segmentation = options.segmentation == Segmentation::Auto;
    if (!a.feet.empty()) options.gait.feet = a.feet;
    if (!a.feet.empty()) options.flight.contacts.feet = a.feet;
    for (const std::string& spec : a.extract) {
        options.extractors.push_back(ParameterExtractor::parse(spec));
        if (!a.feet.empty()) options.extractors.back().contacts.feet = options.gait.feet;
    }
    const auto ids = select_clips(db, db_path, a.clips);
    o.clips = ids.size();
    options.progress = a.progress;
    o.set = build_motion_set(
        ids, [&](const std::string& id) { return db.load_clip(id); }, options, &o.skipped, &o.segmentation);
    if (!a.params_csv.empty()) apply_params_csv(o.set, a.params_csv, db);
    for (const auto& [name, pattern] : a.categories) {
        add_categorical_parameter(o.set, name, levels_from_clip_names(o.set, pattern));
        o.set.parameter_source += (o.set.parameter_source.empty() ? "" : "; ") + ("category:" + name + "=" + pattern);
    }
    for (const auto& [name, period] : a.periodic) set_parameter_period(o.set, name, period);
    validate(o.set);
    check_distinguishable(o.set);
    std::string cached_id;  // samples of one clip are consecutive: one clip loaded at a time
    Clip cached;
    o.twins = find_sample_twins(o.set, [&](std::size_t i) {
        const SampleRef& s = o.set.samples[i];
        if (cached_id != s.clip) {
            cached = db.load_clip(s.clip);
            cached_id = s.clip;
        }
        return sample_frames(o.set, i, cached);
    });
    writer.put_set(o.set, a.replace);
    writer.commit();
    return o;
}

}  // namespace mocapdb::workflow
