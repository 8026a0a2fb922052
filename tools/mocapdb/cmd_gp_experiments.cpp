// `mocapdb gp experiment`: the thesis's experiments (artificial data, CMU replicates), printed as
// tables or JSON.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "gp_cli.hpp"
#include "mocapdb_json/gp_json.hpp"
#include "output_files.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/gp/child_selection.hpp"

namespace mocapdb::cli::gp_cli {
namespace {

namespace fs = std::filesystem;
using namespace mocapdb::gp;

std::string pm(const MeanStd& m, int prec = 3) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f ± %.*f", prec, m.mean, prec, 2.0 * m.std);
    return b;
}

std::string pm(const std::optional<MeanStd>& m) { return m ? pm(*m) : "n/a"; }

}  // namespace

void run_experiment_artificial(const GpArgs& a) {
    if (a.layers == 3)
        throw InvalidArgument(
            "--artificial reproduces the thesis's two-layer experiment; --layers 3 needs real children "
            "(--set or --clips)");
    std::vector<ArtificialConfig> configs = thesis_artificial_configs();
    std::vector<std::size_t> which = a.tests;
    if (which.empty())
        for (std::size_t i = 1; i <= configs.size(); ++i) which.push_back(i);
    ExperimentOptions o;
    o.runs = a.runs;
    o.seed = a.seed;
    o.spec = model_spec(a, true);
    o.fit = fit_options(a, nullptr);
    ProgressBar bar("gp experiment");
    std::vector<ArtificialResult> results;
    for (std::size_t t : which) {
        if (t < 1 || t > configs.size())
            throw InvalidArgument("--tests: expected numbers 1.." + std::to_string(configs.size()));
        o.progress = bar.callback();
        results.push_back(run_artificial(configs[t - 1], o));
    }
    bar.clear();
    if (a.json) {
        JsonWriter w;
        json::write_gp_artificial(w, {a.runs, a.q, a.kernel, which}, results);
        std::cout << w.str();
        return;
    }
    std::printf(
        "artificial interpolation (thesis §5.1.1): %zu runs, 5 of 50 inputs observed on the test child, "
        "models LMC Q=%zu %s; mean ± 2 std over runs\n",
        a.runs, a.q, a.kernel.c_str());
    std::printf("%-5s %-6s %-5s %-6s | %-18s %-18s | %-18s %-18s | %-19s %-19s | fit s\n", "test", "noise", "D", "R",
                "MSE MOHGP", "MSE MOA", "SMSE MOHGP", "SMSE MOA", "MSLL MOHGP", "MSLL MOA");
    for (std::size_t i = 0; i < results.size(); ++i) {
        const auto& r = results[i];
        std::printf("%-5zu %-6g %-5zu %-6zu | %-18s %-18s | %-18s %-18s | %-19s %-19s | %.1f/%.1f\n", which[i],
                    r.config.noise, r.config.outputs, r.config.children, pm(r.mohgp.mse).c_str(), pm(r.moa.mse).c_str(),
                    pm(r.mohgp.smse).c_str(), pm(r.moa.smse).c_str(), pm(r.mohgp.msll).c_str(), pm(r.moa.msll).c_str(),
                    r.mohgp.fit_seconds, r.moa.fit_seconds);
    }
}

void run_experiment_replicates(const GpArgs& a) {
    workflow::GpChildren children = load_children(a);
    const std::size_t n_train = children.clips.size();
    workflow::GpChildren evaluation = workflow::clip_file_children(a.eval_clips, a.fps);
    std::vector<Clip> clips = std::move(children.clips);
    std::vector<std::string> names = std::move(children.names);
    clips.insert(clips.end(), evaluation.clips.begin(), evaluation.clips.end());
    names.insert(names.end(), evaluation.names.begin(), evaluation.names.end());
    // One normalization and dof selection over training and evaluation motions.
    const MotionData all = prepare_motion_data(clips, names, data_options(a));
    ReplicateSplit split = split_replicates(all.data, n_train);
    HgpData& data = split.training;
    const std::vector<MatX>& real = split.real;
    std::vector<std::string> train_names(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(n_train));
    assign_groups(a, train_names, data);
    const std::size_t child = child_index(train_names, a.child);
    ExperimentOptions o;
    o.runs = a.runs;
    o.seed = a.seed;
    o.spec = model_spec(a, true);
    o.fit = fit_options(a, nullptr);
    ProgressBar bar("gp experiment");
    o.progress = bar.callback();
    const ReplicateExperiment experiment = run_replicate_experiment(data, real, child, a.observed_list, a.samples, o);
    bar.clear();
    const ReplicateInterpolation& interp = experiment.interpolation;
    const bool do_synthesis = experiment.synthesis.has_value();
    const SynthesisResult synth = do_synthesis ? *experiment.synthesis : SynthesisResult{};
    if (a.json) {
        json::GpReplicatesReport report{a.layers, train_names[child], a.samples, {}};
        for (std::size_t i = n_train; i < names.size(); ++i) report.real.push_back(names[i]);
        JsonWriter w;
        json::write_gp_replicates(w, report, all, experiment);
        std::cout << w.str();
        return;
    }
    print_data_summary(all);
    std::printf("test child %s; models trained on the other %zu children (LMC Q=%zu %s)\n", train_names[child].c_str(),
                n_train - 1, a.q, a.kernel.c_str());
    if (!data.groups.empty()) {
        std::printf("groups (three layers):");
        for (std::size_t r = 0; r < train_names.size(); ++r)
            std::printf(" %s=%zu", train_names[r].c_str(), data.groups[r]);
        std::printf("\n");
    }
    print_fit_summary(model_label(a), interp.mohgp_fit);
    print_fit_summary("MOA", interp.moa_fit);
    std::printf("%-6s | %-18s %-18s %-19s | %-18s %-18s %-19s\n", "N obs", "MSE MOHGP", "SMSE MOHGP", "MSLL MOHGP",
                "MSE MOA", "SMSE MOA", "MSLL MOA");
    for (const auto& row : interp.rows)
        std::printf("%-6zu | %-18s %-18s %-19s | %-18s %-18s %-19s\n", row.observed, pm(row.mohgp.mse, 4).c_str(),
                    pm(row.mohgp.smse).c_str(), pm(row.mohgp.msll).c_str(), pm(row.moa.mse, 4).c_str(),
                    pm(row.moa.smse).c_str(), pm(row.moa.msll).c_str());
    if (do_synthesis) {
        std::printf(
            "synthesis: %zu samples per model (trained on all %zu children), MCC / MLC mean ± 2 std per real motion;\n"
            "control = the real motions against each other\n",
            a.samples, n_train);
        std::printf("%-16s | %-16s %-16s %-16s | %-15s %-15s %-15s\n", "real", "MCC MOHGP", "MCC MOA", "MCC control",
                    "MLC MOHGP", "MLC MOA", "MLC control");
        for (std::size_t i = 0; i < real.size(); ++i)
            std::printf("%-16s | %-16s %-16s %-16s | %-15s %-15s %-15s\n", names[n_train + i].c_str(),
                        pm(synth.mohgp.mcc[i]).c_str(), pm(synth.moa.mcc[i]).c_str(), pm(synth.control.mcc[i]).c_str(),
                        pm(synth.mohgp.mlc[i]).c_str(), pm(synth.moa.mlc[i]).c_str(), pm(synth.control.mlc[i]).c_str());
    }
}

}  // namespace mocapdb::cli::gp_cli
