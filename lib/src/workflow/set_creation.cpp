#include "mocapdb/workflow/set_creation.hpp"

#include <fnmatch.h>

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

// Fills the set's parameters from a CSV: first column the sample label, then one column per
// parameter, headers "name" or "name[unit]".
void apply_params_csv(MotionSet& set, const std::filesystem::path& path, const Database& db) {
    const std::string file = path.string();
    const CsvTable csv = CsvTable::read(path);
    csv.require_data_rows();
    if (csv.header.size() < 2)
        throw ParseError(file, 1, 0, "expected a header 'sample,p1[,p2...]' with at least one parameter column");
    std::vector<std::string> names(csv.header.begin() + 1, csv.header.end());
    set.parameter_names.clear();
    set.parameter_units.clear();
    set.parameter_periods.resize(0);
    for (const std::string& h : names) {
        const auto [n, u] = name_and_unit(h);
        set.parameter_names.push_back(n);
        set.parameter_units.push_back(u);
    }
    const MatX values = csv.columns(names);
    std::map<std::string, Eigen::Index> row_of;
    for (std::size_t r = 0; r < csv.cells.size(); ++r) {
        if (!row_of.emplace(csv.cells[r][0], static_cast<Eigen::Index>(r)).second)
            throw ParseError(file, csv.line_of_row[r], 1, "sample '" + csv.cells[r][0] + "' appears twice");
    }
    set.parameters.resize(static_cast<Eigen::Index>(set.samples.size()), static_cast<Eigen::Index>(names.size()));
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
        const SampleRef& s = set.samples[i];
        const std::string label = sample_label(s, db.find_clip(s.clip)->frames);
        auto it = row_of.find(label);
        if (it == row_of.end())
            throw ParseError(
                file, 0, 0,
                "no row for sample '" + label + "' (first column: sample labels as 'CLIP' or 'CLIP:BEGIN-END')");
        set.parameters.row(static_cast<Eigen::Index>(i)) = values.row(it->second);
    }
    set.parameter_source = "csv:" + std::filesystem::path(file).filename().string();
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
    if (!a.params_csv.empty() && !a.extract.empty())
        throw Refused<InvalidArgument>(Remedy::ParametersOrExtract,
                                       "give either a parameter table or extractors, not both");
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
