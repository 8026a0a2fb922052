// The steps the `mocapdb gp` subcommands share (gp_cli.hpp).
#include "gp_cli.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "mocapdb/core/error.hpp"
#include "mocapdb/gp/child_selection.hpp"

namespace mocapdb::cli::gp_cli {

namespace fs = std::filesystem;
using namespace mocapdb::gp;

workflow::GpChildren load_children(const GpArgs& a) {
    workflow::GpChildren children;
    if (!a.set.empty()) {
        if (a.db.empty()) throw InvalidArgument("--set needs a database file");
        children = workflow::set_children(a.db, a.set);
    } else {
        children = workflow::clip_file_children(a.clips, a.fps);
    }
    if (children.clips.empty()) throw InvalidArgument("no children: give DB.h5 --set NAME or --clips FILE...");
    return children;
}

MotionDataOptions data_options(const GpArgs& a) {
    MotionDataOptions o;
    o.frames = a.frames;
    if (a.duration > 0.0) o.duration = a.duration;
    o.include_joints = a.joints;
    if (!a.exclude.empty())
        o.exclude_joints = a.exclude == std::vector<std::string>{"none"} ? std::vector<std::string>{} : a.exclude;
    o.drop_noisy = !a.keep_noisy;
    return o;
}

ModelSpec model_spec(const GpArgs& a, bool hierarchical) {
    ModelSpec s;
    s.hierarchical = hierarchical;
    s.grouped = hierarchical && a.layers == 3;
    s.group_terms = a.q;
    s.parent_terms = a.q;
    s.child_terms = a.q;
    s.rank = a.rank;
    s.kernel = kernel_type_from_string(a.kernel);
    return s;
}

FitOptions fit_options(const GpArgs& a, ProgressBar* bar) {
    FitOptions f;
    f.restarts = a.restarts;
    f.max_iterations = a.max_iterations;
    f.seed = a.seed;
    if (bar) f.progress = bar->callback();
    return f;
}

std::size_t child_index(const std::vector<std::string>& names, const std::string& which) {
    if (const auto i = find_child(names, which)) return *i;
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InvalidArgument("no child '" + which + "' (children: " + list + "; or an index from 0)");
}

/// Three layers: each child's group, from --groups or from the subject in its CMU name (groups numbered
/// in order of first appearance). Nothing for two layers or the MOA baseline.
void assign_groups(const GpArgs& a, const std::vector<std::string>& names, HgpData& data) {
    data.groups.clear();
    if (a.layers != 3 || a.mo_baseline) return;
    if (!a.groups.empty()) {
        if (a.groups.size() != names.size())
            throw InvalidArgument("--groups: " + std::to_string(a.groups.size()) + " values for " +
                                  std::to_string(names.size()) + " children (one group index per child)");
        data.groups = a.groups;
        validate(data);
        return;
    }
    for (const auto& n : names)
        if (subject_of(n).empty())
            throw InvalidArgument("--layers 3: cannot tell the subject of child '" + n +
                                  "' (expected a CMU name like 02_01); give --groups with one index per child");
    data.groups = groups_by_subject(names);
}

const char* model_label(const GpArgs& a) {
    return a.mo_baseline ? "MOA" : a.layers == 3 ? "MOHGP (3 layers)" : "MOHGP";
}

void print_fit_summary(const char* label, const FitResult& f) {
    std::printf("%s: log likelihood %.4f, %s, %d evaluations, %.2f s\n", label, f.log_likelihood,
                to_string(f.status).c_str(), f.evaluations, f.seconds);
    const ModelSummary summary = summarize_model(f.model);
    auto terms = [](const char* layer, const std::vector<TermSummary>& layer_terms) {
        for (std::size_t q = 0; q < layer_terms.size(); ++q)
            std::printf("  %s q%zu: %s lengthscale %.4g s, mean B diagonal %.4g\n", layer, q,
                        to_string(layer_terms[q].kernel).c_str(), layer_terms[q].lengthscale_s,
                        layer_terms[q].mean_b_diagonal);
    };
    terms("parent", summary.parent);
    terms("group ", summary.group);
    terms(f.model.hierarchical ? "child " : "MOA   ", summary.child);
    std::printf("  noise variance: mean %.3g (min %.3g, max %.3g)\n", summary.noise_mean, summary.noise_min,
                summary.noise_max);
}

void print_data_summary(const MotionData& md) {
    std::printf("children: %zu (", md.child_names.size());
    for (std::size_t i = 0; i < md.child_names.size(); ++i)
        std::printf("%s%s", i ? ", " : "", md.child_names[i].c_str());
    std::printf("); %zu dofs x %zu frames over %.3f s (%zu dofs dropped)\n", md.dofs.size(), md.data.frames(),
                md.data.times[md.data.times.size() - 1], md.dropped.size());
    if (!md.data.groups.empty()) {
        std::printf("groups (three layers):");
        for (std::size_t g = 0; g < md.data.group_count(); ++g) {
            std::printf(" %zu = {", g);
            bool first = true;
            for (std::size_t r = 0; r < md.data.child_count(); ++r)
                if (md.data.groups[r] == g) {
                    std::printf("%s%s", first ? "" : ", ", md.child_names[r].c_str());
                    first = false;
                }
            std::printf("}");
        }
        std::printf("\n");
    }
}

}  // namespace mocapdb::cli::gp_cli
