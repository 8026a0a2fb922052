// mocapdb set create|list|show: motion sets (samples + control parameters) in a database.
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "option_lists.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/database_json.hpp"
#include "mocapdb_json/step_json.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/dropout_repair.hpp"
#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/store/database.hpp"
#include "pipeline.hpp"

namespace mocapdb::cli {
namespace {

struct CreateArgs {
    std::string db;
    SetRequest request;
    std::vector<std::string> periodic;  ///< NAME=PERIOD, parsed into request.periodic
    std::vector<std::string> category;  ///< NAME=REGEX, parsed into request.categories
    std::string feet;                   ///< left,right, split into request.feet
    bool json = false;
};

// One warning line per group of twins (samples showing the same frames), on stderr.
void warn_twins(const SetOutcome& o) {
    const std::size_t shown = 20;
    const auto& groups = o.twins.groups;
    for (std::size_t g = 0; g < groups.size() && g < shown; ++g) {
        bool same_clip = true;
        for (const TwinPair& p : o.twins.pairs)
            if (!p.same_clip && std::find(groups[g].begin(), groups[g].end(), p.a) != groups[g].end())
                same_clip = false;
        std::string names;
        for (std::size_t i : groups[g]) names += (names.empty() ? "" : ", ") + sample_label(o.set.samples[i], 0);
        if (same_clip)
            std::fprintf(stderr, "warning: set '%s': samples %s overlap (the same frames of one clip)",
                         o.set.name.c_str(), names.c_str());
        else
            std::fprintf(stderr,
                         "warning: set '%s': samples %s show the same frames (within %g cm: a clip imported twice?)",
                         o.set.name.c_str(), names.c_str(), TwinOptions{}.tolerance_cm);
        std::fprintf(stderr, "; leave-one-out (mocapdb eval) leaves them out together\n");
    }
    if (groups.size() > shown)
        std::fprintf(stderr, "warning: set '%s': %zu more groups of twins (--json lists them all)\n",
                     o.set.name.c_str(), groups.size() - shown);
}

void run_create(CreateArgs a) {
    a.request.periodic = periodic_parameters(a.periodic);
    a.request.categories = category_parameters(a.category);
    if (!a.feet.empty()) a.request.feet = split_names(a.feet, "--feet");
    const SetOutcome o = create_set(a.db, a.request);
    warn_twins(o);
    if (a.json) {
        JsonWriter j;
        json::write_set(j, o);
        std::fputs(j.str().c_str(), stdout);
        return;
    }
    std::fputs(describe_set(o).c_str(), stdout);
}

void print_set(const Database& db, const std::string& name, bool json) {
    const MotionSet set = db.load_set(name);
    std::vector<std::string> labels;
    for (const SampleRef& s : set.samples) labels.push_back(sample_label(s, db.find_clip(s.clip)->frames));
    const auto aligned = db.load_aligned(name);
    const auto kernel = db.load_kernel_fit(name);
    const std::optional<synthesis::PredictorChoice> predictor = kernel ? kernel->predictor : std::nullopt;
    const std::optional<synthesis::EdgeWarning> edge = kernel ? kernel->edge_warning : std::nullopt;
    if (json) {
        JsonWriter j;
        json::write_set_show(j, set, labels, aligned, predictor, edge);
        std::cout << j.str();
        return;
    }
    std::printf("set %s: %zu samples, parameters from %s\n", set.name.c_str(), set.samples.size(),
                set.parameter_source.empty() ? "nowhere" : set.parameter_source.c_str());
    if (aligned)
        std::printf("aligned: %s, %lld frames, %lld dofs, reference sample %zu\n", aligned->method.c_str(),
                    static_cast<long long>(aligned->frames()), static_cast<long long>(aligned->dofs()),
                    aligned->reference);
    if (predictor) std::printf("synthesis predictor: %s\n", synthesis::describe(*predictor).c_str());
    if (edge) std::printf("reliability: %s\n", synthesis::describe(*edge).c_str());
    std::printf("%-22s", "sample");
    for (std::size_t p = 0; p < set.parameter_names.size(); ++p) {
        const std::string h =
            set.parameter_names[p] + (set.parameter_units[p].empty() ? "" : " [" + set.parameter_units[p] + "]");
        std::printf(" %14s", h.c_str());
    }
    std::printf("\n");
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
        std::printf("%-22s", labels[i].c_str());
        for (Eigen::Index p = 0; p < set.parameters.cols(); ++p) {
            const double v = set.parameters(static_cast<Eigen::Index>(i), p);
            if (is_categorical(set, static_cast<std::size_t>(p)))
                std::printf(" %14s",
                            set.parameter_levels[static_cast<std::size_t>(p)][static_cast<std::size_t>(v)].c_str());
            else std::printf(" %14.4f", v);
        }
        std::printf("\n");
    }
    for (Eigen::Index p = 0; p < set.parameter_periods.size(); ++p) {
        if (!(set.parameter_periods(p) > 0.0)) continue;
        std::printf("periodic: %s, period %g %s\n", set.parameter_names[static_cast<std::size_t>(p)].c_str(),
                    set.parameter_periods(p), set.parameter_units[static_cast<std::size_t>(p)].c_str());
    }
    for (std::size_t p = 0; p < set.parameter_levels.size(); ++p) {
        if (!is_categorical(set, p)) continue;
        std::string levels;
        for (const std::string& l : set.parameter_levels[p]) levels += (levels.empty() ? "" : ", ") + l;
        std::printf("categorical: %s, levels %s\n", set.parameter_names[p].c_str(), levels.c_str());
    }
    if (!set.dropouts_checked) {
        std::printf("dropouts: not checked (set stored before the check; 'set create --force' rebuilds it)\n");
        return;
    }
    if (set.repairs.empty()) {
        std::printf("dropouts: none found\n");
        return;
    }
    const std::vector<std::string> clips = summarize_repairs(set.repairs).clips;
    std::printf("repaired dropouts (joint rotations interpolated from the clean frames; frames 0-based, inclusive):\n");
    for (const std::string& c : clips) std::printf("  %-20s %s\n", c.c_str(), describe_repairs(c, set.repairs).c_str());
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
        "  mocapdb set create db.h5 --name walks1 --clips '16_1[1-9]' --segment gait:1 --extract speed turn\n"
        "  mocapdb set create db.h5 --name jumps --clips '16_0[5-9]' --segment flight:0.5:0.5 --extract jump\n"
        "  mocapdb set create db.h5 --name dirs --clips 'strafe_*' --segment gait:1 --extract bearing speed\n"
        "  mocapdb set create db.h5 --name reach --clips 'reach_*' --params targets.csv\n"
        "  mocapdb set create db.h5 --name gaits --clips '16_1[235]*' '16_3[579]*' --extract turn\n"
        "      --category 'gait=^16_([13])'\n"
        "Extractors: displacement (dx, dz cm), turn (rad), speed (cm/s), jump (cm), reach:JOINT@FRAME (cm;\n"
        "FRAME = offset, end or P%); definitions in lib/include/mocapdb/dataset/param_extractors.hpp.\n"
        "Segmentation: auto (default: flights when a jump is extracted; else gait cycles when parameters are\n"
        "extracted and at least 80 % of the clips have one; else whole clips), none (whole clips), gait[:N] (gait\n"
        "cycles from one forward pass of the left foot past the right to the next, so every sample starts at the\n"
        "same phase; at most N per clip, evenly spread, 1 = the middle one), window:LENGTH[:HOP] (frames),\n"
        "flight[:BEFORE[:AFTER]] (the clip's longest flight with BEFORE s before take-off and AFTER s after landing,\n"
        "default 0.5 each: every jump sample starts the same time before its take-off). Params CSV: header\n"
        "'sample,name[unit],...', one row per sample labelled CLIP (whole clip) or CLIP:BEGIN-END; a column of\n"
        "names (no numbers) is a categorical parameter. Parameters: extracted, then the CSV's, then categories.\n"
        "--category NAME=REGEX: the level of each sample is the first group of REGEX (ECMAScript) searched in\n"
        "its clip id; every level needs at least 2 samples. Categories: docs/synthesis.md.");
    create->add_option("db", c->db, "database file")->required();
    create->add_option("--name", c->request.name, "set name")->required();
    create->add_option("--clips", c->request.clips, "clip ids or shell patterns (quoted), in sample order")->required();
    create->add_option("--params", c->request.params_csv, "control parameters from a CSV")->check(CLI::ExistingFile);
    create->add_option("--extract", c->request.extract, "control parameters measured from the motion");
    create->add_option("--category", c->category,
                       "NAME=REGEX: a categorical parameter whose level is REGEX's first group in the clip id");
    create->add_option(
        "--periodic", c->periodic,
        "NAME=PERIOD: a periodic parameter (e.g. bearing=360 for degrees); 'bearing' extracted is periodic by itself");
    create->add_option("--segment", c->request.segment,
                       "auto | none | gait[:N] | window:LENGTH[:HOP] | flight[:BEFORE[:AFTER]] (default auto)");
    create->add_option(
        "--feet", c->feet,
        "left,right foot joints for gait cycles and contacts, e.g. ltoes,rtoes (default: found by name)");
    create->add_flag("--force,--replace", c->request.replace, "replace an existing set of that name");
    create->add_flag("--json", c->json, "print one JSON object (the keys of Python's mocapdb.create_set)");
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
            json::write_set_list(j, sets);
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
    show->add_flag(
        "--json", *show_json,
        "print JSON: {name, parameter_source, parameters:[{name,unit,[period],[levels]}], aligned, samples:[{label,clip,begin,end,values}],\n"
        "dropouts_checked, repairs:[{clip,joint,begin,end}]} (repaired solver dropouts, frames [begin, end))");
    show->callback([show_db, show_name, show_json] { print_set(Database(*show_db), *show_name, *show_json); });
}

}  // namespace mocapdb::cli
