// mocapdb set create|list|show: motion sets (samples + control parameters) in a database.
#include <fnmatch.h>

#include <cstdio>
#include <iostream>
#include <map>
#include <set>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/store/database.hpp"
#include "numeric_csv.hpp"

namespace mocapdb::cli {
namespace {

struct CreateArgs {
    std::string db;
    std::string name;
    std::vector<std::string> clips;
    std::string params_csv;
    std::vector<std::string> extract;
    std::string segment = "none";
    std::string feet;
    bool replace = false;
};

// Clip ids matching the patterns, in pattern order (ids sorted within a pattern), each once.
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
        if (!matched) throw InvalidArgument(db_name + ": no clip matches '" + pattern + "' (mocapdb info " + db_name + " lists them)");
    }
    return out;
}

// Splits "NAME[UNIT]" into name and unit.
std::pair<std::string, std::string> name_and_unit(const std::string& header) {
    const auto open = header.find('[');
    if (open == std::string::npos || header.back() != ']') return {header, ""};
    return {header.substr(0, open), header.substr(open + 1, header.size() - open - 2)};
}

// Fills the set's parameters from a CSV: first column the sample label, then one column per
// parameter, headers "name" or "name[unit]".
void apply_params_csv(MotionSet& set, const std::string& file, const Database& db) {
    const NumericCsv csv = NumericCsv::read(file);
    if (csv.header.size() < 2)
        throw ParseError(file, 1, 0, "expected a header 'sample,p1[,p2...]' with at least one parameter column");
    std::vector<std::string> names(csv.header.begin() + 1, csv.header.end());
    set.parameter_names.clear();
    set.parameter_units.clear();
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
            throw ParseError(file, 0, 0, "no row for sample '" + label + "' (first column: sample labels as 'CLIP' or 'CLIP:BEGIN-END')");
        set.parameters.row(static_cast<Eigen::Index>(i)) = values.row(it->second);
    }
    set.parameter_source = "csv:" + std::filesystem::path(file).filename().string();
}

void run_create(const CreateArgs& a) {
    if (!a.params_csv.empty() && !a.extract.empty())
        throw InvalidArgument("give either --params or --extract, not both");
    DatabaseWriter writer(a.db, DatabaseWriter::Mode::OpenOrCreate);
    const Database& db = writer.view();
    if (db.clips().empty()) throw InvalidArgument(a.db + ": the database holds no clips; import some first");
    if (db.has_set(a.name) && !a.replace)
        throw InvalidArgument(a.db + ": set '" + a.name + "' exists; pass --force to replace it");
    SetBuildOptions options;
    options.name = a.name;
    parse_segmentation(a.segment, options);
    if (!a.feet.empty()) options.gait.contacts.feet = split_names(a.feet, "--feet");
    for (const std::string& spec : a.extract) {
        options.extractors.push_back(ParameterExtractor::parse(spec));
        if (!a.feet.empty()) options.extractors.back().contacts.feet = options.gait.contacts.feet;
    }
    const auto ids = select_clips(db, a.db, a.clips);
    std::vector<std::string> skipped;
    MotionSet set = build_motion_set(ids, [&](const std::string& id) { return db.load_clip(id); }, options, &skipped);
    for (const std::string& id : skipped)
        std::cerr << "mocapdb: warning: clip '" << id << "' yields no sample (" << a.segment << ") and is left out\n";
    if (!a.params_csv.empty()) apply_params_csv(set, a.params_csv, db);
    validate(set);
    writer.put_set(set, a.replace);
    writer.commit();
    std::printf("set '%s': %zu samples from %zu clips, %zu parameters (%s)\n", set.name.c_str(), set.samples.size(),
                ids.size(), set.parameter_names.size(),
                set.parameter_source.empty() ? "none" : set.parameter_source.c_str());
}

void print_set(const Database& db, const std::string& name, bool json) {
    const MotionSet set = db.load_set(name);
    std::vector<std::string> labels;
    for (const SampleRef& s : set.samples) labels.push_back(sample_label(s, db.find_clip(s.clip)->frames));
    const auto aligned = db.load_aligned(name);
    if (json) {
        JsonWriter j;
        j.begin_object();
        j.key("name").value(set.name);
        j.key("parameter_source").value(set.parameter_source);
        j.key("parameters").begin_array();
        for (std::size_t p = 0; p < set.parameter_names.size(); ++p)
            j.begin_object().key("name").value(set.parameter_names[p]).key("unit").value(set.parameter_units[p]).end_object();
        j.end_array();
        j.key("aligned").value(aligned.has_value());
        if (aligned) {
            j.key("method").value(aligned->method);
            j.key("frames").value(static_cast<long long>(aligned->frames()));
            j.key("dofs").value(static_cast<long long>(aligned->dofs()));
            j.key("reference").value(aligned->reference);
        }
        j.key("samples").begin_array();
        for (std::size_t i = 0; i < set.samples.size(); ++i) {
            const SampleRef& s = set.samples[i];
            j.begin_object().key("label").value(labels[i]).key("clip").value(s.clip);
            j.key("begin").value(s.begin).key("end").value(s.end);
            j.key("values").begin_array();
            for (Eigen::Index p = 0; p < set.parameters.cols(); ++p) j.value(set.parameters(static_cast<Eigen::Index>(i), p));
            j.end_array().end_object();
        }
        j.end_array().end_object();
        std::cout << j.str();
        return;
    }
    std::printf("set %s: %zu samples, parameters from %s\n", set.name.c_str(), set.samples.size(),
                set.parameter_source.empty() ? "nowhere" : set.parameter_source.c_str());
    if (aligned)
        std::printf("aligned: %s, %lld frames, %lld dofs, reference sample %zu\n", aligned->method.c_str(),
                    static_cast<long long>(aligned->frames()), static_cast<long long>(aligned->dofs()), aligned->reference);
    std::printf("%-22s", "sample");
    for (std::size_t p = 0; p < set.parameter_names.size(); ++p) {
        const std::string h = set.parameter_names[p] + (set.parameter_units[p].empty() ? "" : " [" + set.parameter_units[p] + "]");
        std::printf(" %14s", h.c_str());
    }
    std::printf("\n");
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
        std::printf("%-22s", labels[i].c_str());
        for (Eigen::Index p = 0; p < set.parameters.cols(); ++p) std::printf(" %14.4f", set.parameters(static_cast<Eigen::Index>(i), p));
        std::printf("\n");
    }
}

}  // namespace

void setup_set(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("set", "Motion sets: samples of stored clips with control parameters");
    cmd->require_subcommand(1);

    auto c = std::make_shared<CreateArgs>();
    CLI::App* create = cmd->add_subcommand("create", "Create a motion set from stored clips");
    create->footer(
        "Examples:\n"
        "  mocapdb set create db.h5 --name walks --clips '16_1[1-9]' '16_2?' 16_30 --extract turn speed\n"
        "  mocapdb set create db.h5 --name cycles --clips '105_0[1-8]' --segment gait --extract speed turn\n"
        "  mocapdb set create db.h5 --name reach --clips 'reach_*' --params targets.csv\n"
        "Extractors: displacement (dx, dz cm), turn (rad), speed (cm/s), jump (cm), reach:JOINT@FRAME (cm;\n"
        "FRAME = offset, end or P%); definitions in lib/include/mocapdb/dataset/param_extractors.hpp.\n"
        "Segmentation: none (whole clips), gait (touch-down to touch-down of the first foot),\n"
        "window:LENGTH[:HOP] (frames). Params CSV: header 'sample,name[unit],...', one row per sample\n"
        "labelled CLIP (whole clip) or CLIP:BEGIN-END.");
    create->add_option("db", c->db, "database file")->required();
    create->add_option("--name", c->name, "set name")->required();
    create->add_option("--clips", c->clips, "clip ids or shell patterns (quoted), in sample order")->required();
    create->add_option("--params", c->params_csv, "control parameters from a CSV")->check(CLI::ExistingFile);
    create->add_option("--extract", c->extract, "control parameters measured from the motion");
    create->add_option("--segment", c->segment, "none | gait | window:LENGTH[:HOP]");
    create->add_option("--feet", c->feet, "foot joints for contacts, e.g. ltoes,rtoes (default: found by name)");
    create->add_flag("--force,--replace", c->replace, "replace an existing set of that name");
    create->callback([c] { run_create(*c); });

    auto list_db = std::make_shared<std::string>();
    auto list_json = std::make_shared<bool>(false);
    CLI::App* list = cmd->add_subcommand("list", "List the motion sets of a database");
    list->add_option("db", *list_db, "database file")->required()->check(CLI::ExistingFile);
    list->add_flag("--json", *list_json, "print JSON: [{name, samples, parameters, aligned, model, model_ranks}]");
    list->callback([list_db, list_json] {
        const Database db(*list_db);
        const auto sets = db.sets();
        if (*list_json) {
            JsonWriter j;
            j.begin_array();
            for (const SetRecord& s : sets) {
                j.begin_object().key("name").value(s.name).key("samples").value(s.samples);
                j.key("parameters").begin_array();
                for (const auto& p : s.parameter_names) j.value(p);
                j.end_array().key("aligned").value(s.aligned).key("model").value(s.model);
                if (s.model) {
                    j.key("model_ranks").begin_array();
                    for (std::size_t r : s.model_ranks) j.value(r);
                    j.end_array();
                } else {
                    j.key("model_ranks").null();
                }
                j.end_object();
            }
            j.end_array();
            std::cout << j.str();
            return;
        }
        if (sets.empty()) std::printf("no motion sets in %s\n", list_db->c_str());
        for (const SetRecord& s : sets) {
            std::string params;
            for (const auto& p : s.parameter_names) params += (params.empty() ? "" : ",") + p;
            std::string state = s.aligned ? "aligned" : "not aligned";
            if (s.model)
                state += ", model " + std::to_string(s.model_ranks[0]) + "x" + std::to_string(s.model_ranks[1]) + "x" +
                         std::to_string(s.model_ranks[2]);
            std::printf("%-20s %5zu samples  params %-24s %s\n", s.name.c_str(), s.samples, params.c_str(),
                        state.c_str());
        }
    });

    auto show_db = std::make_shared<std::string>();
    auto show_name = std::make_shared<std::string>();
    auto show_json = std::make_shared<bool>(false);
    CLI::App* show = cmd->add_subcommand("show", "Show a motion set's samples and control parameters");
    show->add_option("db", *show_db, "database file")->required()->check(CLI::ExistingFile);
    show->add_option("name", *show_name, "set name")->required();
    show->add_flag("--json", *show_json,
                   "print JSON: {name, parameter_source, parameters:[{name,unit}], aligned, samples:[{label,clip,begin,end,values}]}");
    show->callback([show_db, show_name, show_json] { print_set(Database(*show_db), *show_name, *show_json); });
}

}  // namespace mocapdb::cli
