// mocapdb gp: hierarchical multi-output Gaussian processes (MOHGP) over replicate motions — fit,
// interpolate a partially observed child, sample new children, and the thesis's experiments.
// No model file is written: every subcommand fits the model it needs (deterministically: same data
// and options give the same fit).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "clip_options.hpp"
#include "commands.hpp"
#include "gp_cli.hpp"
#include "mocapdb_json/gp_json.hpp"
#include "output_files.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/core/keep_freed_memory.hpp"
#include "mocapdb/gp/child_selection.hpp"
#include "mocapdb/io/bvh.hpp"

namespace mocapdb::cli {
namespace gp_cli {

namespace fs = std::filesystem;
using namespace mocapdb::gp;

namespace {

/// The group of --subject: a subject of the CMU names (e.g. 16), or with --groups a group index.
std::size_t subject_group(const GpArgs& a, const std::vector<std::string>& names, const HgpData& data) {
    if (a.layers != 3 || a.mo_baseline) throw InvalidArgument("--subject needs --layers 3 (and not --mo-baseline)");
    if (!a.groups.empty()) {
        std::size_t pos = 0;
        unsigned long v = 0;
        try {
            v = std::stoul(a.subject, &pos);
        } catch (const std::exception&) {
            pos = 0;
        }
        if (pos != a.subject.size() || v >= data.group_count())
            throw InvalidArgument("--subject '" + a.subject + "': with --groups give a group index 0.." +
                                  std::to_string(data.group_count() - 1));
        return v;
    }
    if (const auto g = group_of_subject(names, data.groups, a.subject)) return *g;
    std::string known;
    for (const std::string& s : distinct_subjects(names)) known += (known.empty() ? " " : ", ") + s;
    throw InvalidArgument("--subject '" + a.subject + "': no child of that subject (subjects:" + known + ")");
}

const char* model_name(const GpArgs& a) { return a.mo_baseline ? "moa" : a.layers == 3 ? "mohgp3" : "mohgp"; }
void run_fit(const GpArgs& a) {
    const workflow::GpChildren children = load_children(a);
    MotionData md = prepare_motion_data(children.clips, children.names, data_options(a));
    assign_groups(a, md.child_names, md.data);
    ProgressBar bar("gp fit");
    const FitResult f = fit_model(md.data, model_spec(a, !a.mo_baseline), fit_options(a, &bar));
    bar.clear();
    if (a.json) {
        JsonWriter w;
        json::write_gp_fit(w, model_name(a), md, f);
        std::cout << w.str();
        return;
    }
    print_data_summary(md);
    print_fit_summary(model_label(a), f);
}

void run_interpolate(const GpArgs& a) {
    const workflow::GpChildren children = load_children(a);
    MotionData md = prepare_motion_data(children.clips, children.names, data_options(a));
    assign_groups(a, md.child_names, md.data);
    const std::size_t child = child_index(md.child_names, a.child);
    if (md.data.child_count() < 2) throw InvalidArgument("interpolate needs ≥ 2 children (the others train the model)");
    if (a.observed + 2 > md.data.frames())
        throw InvalidArgument("--observed " + std::to_string(a.observed) + " leaves fewer than 2 of " +
                              std::to_string(md.data.frames()) + " frames to predict");
    if (!a.out.empty()) refuse_existing(a.out, a.force);
    ProgressBar bar("gp interpolate");
    const ChildInterpolation interpolation =
        interpolate_child(md.data, child, a.observed, model_spec(a, !a.mo_baseline), fit_options(a, &bar), a.seed);
    bar.clear();
    const FitResult& f = interpolation.fit;
    const InterpolationScores& s = interpolation.scores;
    const GaussianPrediction& p = interpolation.prediction;
    if (!a.out.empty())
        write_bvh(fs::path(a.out), reassemble_clip(md, p.mean, md.child_names[child] + "-interpolated"));
    if (a.json) {
        JsonWriter w;
        json::write_gp_interpolation(w, model_name(a), md, md.child_names[child], interpolation);
        std::cout << w.str();
        return;
    }
    print_data_summary(md);
    print_fit_summary(model_label(a), f);
    char smse[32] = "n/a";
    if (s.smse) std::snprintf(smse, sizeof smse, "%.4f", *s.smse);
    std::printf("child %s, %zu of %zu frames observed: MSE %.5f  SMSE %s  MSLL %.4f (%zu values predicted)\n",
                md.child_names[child].c_str(), a.observed, md.data.frames(), s.mse, smse, s.msll, s.points);
    if (!a.out.empty()) std::printf("wrote %s\n", a.out.c_str());
}

void run_sample(const GpArgs& a) {
    const workflow::GpChildren children = load_children(a);
    MotionData md = prepare_motion_data(children.clips, children.names, data_options(a));
    assign_groups(a, md.child_names, md.data);
    std::optional<std::size_t> group;
    if (!a.subject.empty()) group = subject_group(a, md.child_names, md.data);
    if (a.out.empty()) throw InvalidArgument("sample needs -o DIR");
    const fs::path dir(a.out);
    if (fs::exists(dir) && !fs::is_directory(dir)) throw IoError(dir.string() + ": not a directory");
    fs::create_directories(dir);
    std::vector<fs::path> files;
    for (std::size_t i = 0; i < a.n; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "sample_%03zu.bvh", i + 1);
        files.push_back(dir / name);
    }
    files.push_back(dir / "trend.bvh");
    for (const auto& p : files) refuse_existing(p, a.force);
    SampleOptions so;
    so.seed = a.seed;
    so.group = group;
    ProgressBar bar("gp sample");
    const NewChildren drawn =
        sample_new_children(md.data, model_spec(a, !a.mo_baseline), fit_options(a, &bar), a.n, so);
    bar.clear();
    const FitResult& f = drawn.fit;
    const std::vector<MatX>& samples = drawn.samples;
    for (std::size_t i = 0; i < samples.size(); ++i)
        write_bvh(files[i], reassemble_clip(md, samples[i], files[i].stem().string()));
    write_bvh(files.back(), reassemble_clip(md, drawn.trend, "trend"));
    if (a.json) {
        std::vector<std::string> names;
        for (const auto& p : files) names.push_back(p.string());
        JsonWriter w;
        json::write_gp_samples(w, model_name(a), md, names, f);
        std::cout << w.str();
        return;
    }
    print_data_summary(md);
    print_fit_summary(model_label(a), f);
    std::printf("wrote %zu samples and the trend to %s\n", samples.size(), dir.string().c_str());
}

void add_source_options(CLI::App* cmd, GpArgs& a) {
    cmd->add_option("db", a.db, "database file (with --set)");
    cmd->add_option("--set", a.set, "motion set: its samples are the children");
    cmd->add_option("--clips", a.clips, "clip files (BVH, or AMC with the ASF beside it) as the children")
        ->check(CLI::ExistingFile);
    cmd->add_option("--fps", a.fps, "frame rate override for the clip files (Hz)")->check(frame_rate_check());
    cmd->add_option("--frames", a.frames, "subsampled frames per child (default 90)")->check(CLI::Range(2, 100000));
    cmd->add_option("--duration", a.duration, "seconds from each child's start (default: the shortest child)");
    cmd->add_option("--joints", a.joints, "only these joints' dofs (names; the root name selects the 6 root dofs)")
        ->delimiter(',');
    cmd->add_option("--exclude-joints", a.exclude,
                    "joints left out (default: clavicles, wrists, hands, fingers, thumbs, toes; 'none' keeps all)")
        ->delimiter(',');
    cmd->add_flag("--keep-noisy", a.keep_noisy, "keep dofs with a negative log SNR");
}

void add_model_options(CLI::App* cmd, GpArgs& a) {
    cmd->add_option("--layers", a.layers,
                    "2: trend -> child (default); 3: trend -> subject -> trial, subjects from the CMU names "
                    "(02_01 -> 02) or --groups")
        ->check(CLI::IsMember({2, 3}));
    cmd->add_option("--groups", a.groups, "with --layers 3: one group index per child (0-based), e.g. 0,0,1,1")
        ->delimiter(',');
    cmd->add_option("--q", a.q, "LMC terms per layer (default 1 = ICM)")->check(CLI::Range(1, 10));
    cmd->add_option("--rank", a.rank, "rank of every W_q (default 1)")->check(CLI::Range(1, 50));
    cmd->add_option("--kernel", a.kernel, "rbf | matern32 (default matern32)")
        ->check(CLI::IsMember({"rbf", "matern32"}));
    cmd->add_option("--restarts", a.restarts, "optimizer restarts (deterministic; default 1)")
        ->check(CLI::Range(1, 100));
    cmd->add_option("--max-iterations", a.max_iterations, "L-BFGS iterations per restart (default 300)")
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--seed", a.seed, "seed of restarts, observed frames and samples (default 1)");
    cmd->add_flag("--json", a.json, "machine-readable output on stdout");
}

}  // namespace
}  // namespace gp_cli

using namespace gp_cli;

void setup_gp(CLI::App& app) {
    auto a = std::make_shared<GpArgs>();
    CLI::App* gp = app.add_subcommand("gp", "Hierarchical multi-output Gaussian processes over replicate motions");
    gp->require_subcommand(1);
    gp->footer(
        "Children are the samples of a set (DB.h5 --set NAME) or clip files (--clips ...). Each is converted to\n"
        "pose vectors, subsampled to --frames frames, dofs selected and min-max normalized (docs/gp.md).\n"
        "No model file is written: each subcommand fits the model it uses (deterministic for given options).\n"
        "--layers 3 adds a subject layer (trend -> subject -> trial): subjects from the CMU names (02_01 -> 02)\n"
        "or --groups, one index per child.");

    CLI::App* fitc = gp->add_subcommand("fit", "Fit a MOHGP (or the MOA baseline) and print its parameters");
    add_source_options(fitc, *a);
    add_model_options(fitc, *a);
    fitc->add_flag("--mo-baseline", a->mo_baseline, "fit the flat multi-output GP (MOA) instead");
    fitc->footer(
        "Example:\n  mocapdb gp fit db.h5 --set walks --q 1 --kernel matern32 --json\n"
        "JSON keys: model, children, frames, duration_s, dofs, log_likelihood, status, seconds, evaluations,\n"
        "restarts[], noise_variance[], parameters{name: value}.");
    fitc->callback([a] {
        keep_freed_memory();
        run_fit(*a);
    });

    CLI::App* interp = gp->add_subcommand("interpolate", "Predict a child from some of its frames and its siblings");
    add_source_options(interp, *a);
    add_model_options(interp, *a);
    interp->add_flag("--mo-baseline", a->mo_baseline, "use the flat multi-output GP (MOA)");
    interp->add_option("--child", a->child, "the child to interpolate: name or index (default 0)");
    interp->add_option("--observed", a->observed, "observed frames of that child, chosen at random (--seed)");
    interp->add_option("-o,--output", a->out, "write the interpolated child as BVH");
    interp->add_flag("--force", a->force, "overwrite the output");
    interp->footer(
        "Example:\n  mocapdb gp interpolate --clips 02_01.amc 02_02.amc 35_01.amc --child 02_01 --observed 40\n"
        "The model is fitted to the other children; the child's observed frames condition its posterior.\n"
        "JSON keys: model, children, frames, duration_s, dofs, child, observed_frames[], mse, smse, msll,\n"
        "predicted_values, fit{...}, mean[D][T] (normalized units).");
    interp->callback([a] {
        keep_freed_memory();
        run_interpolate(*a);
    });

    CLI::App* samp = gp->add_subcommand("sample", "Synthesize new children around the inferred parent (BVH files)");
    add_source_options(samp, *a);
    add_model_options(samp, *a);
    samp->add_flag("--mo-baseline", a->mo_baseline, "use the flat multi-output GP (MOA)");
    samp->add_option("--n", a->n, "number of samples (default 10)")->check(CLI::Range(1, 10000));
    samp->add_option(
        "--subject", a->subject,
        "with --layers 3: new trials of this subject (e.g. 16; with --groups a group index) instead of a new subject");
    samp->add_option("-o,--output", a->out, "output folder (sample_001.bvh ..., trend.bvh)")->required();
    samp->add_flag("--force", a->force, "overwrite existing files");
    samp->footer(
        "Example:\n  mocapdb gp sample db.h5 --set walks --n 5 -o samples/\n"
        "Samples are the parent's posterior mean plus a draw of the child process (thesis §5.2). With --layers 3\n"
        "a sample is a new trial of a new subject (trend + subject and trial processes), or with --subject S a\n"
        "new trial of subject S (its posterior mean + the trial process).");
    samp->callback([a] {
        keep_freed_memory();
        run_sample(*a);
    });

    CLI::App* exp = gp->add_subcommand("experiment", "Reproduce the thesis's interpolation and synthesis tables");
    add_source_options(exp, *a);
    add_model_options(exp, *a);
    exp->add_flag("--artificial", a->artificial, "the artificial-data table (thesis §5.1.1, Tables 1-3)");
    exp->add_option("--tests", a->tests, "with --artificial: which of the 9 tests (1-based; default all)")
        ->delimiter(',');
    exp->add_option("--runs", a->runs, "validation runs (default 5)")->check(CLI::Range(1, 1000));
    exp->add_option("--child", a->child, "test child for interpolation (name or index; default 0)");
    exp->add_option("--observed-list", a->observed_list, "observed frames per test (default 40,30,20,10)")
        ->delimiter(',');
    exp->add_option("--eval-clips", a->eval_clips, "real motions to score synthesized samples against")
        ->check(CLI::ExistingFile);
    exp->add_option("--samples", a->samples, "synthesized samples per model (default 25)");
    exp->footer(
        "Examples:\n  mocapdb gp experiment --artificial --q 3 --kernel rbf --json\n"
        "  mocapdb gp experiment --clips 02_01.amc 02_02.amc 35_01.amc --child 02_01 --eval-clips 16_15.amc 16_16.amc\n"
        "Training uses the complete children; the test child's observed frames enter its posterior only.\n"
        "Tables print mean ± 2 std over the runs (the thesis's convention); JSON gives mean and std.");
    exp->callback([a] {
        keep_freed_memory();
        if (a->artificial) run_experiment_artificial(*a);
        else run_experiment_replicates(*a);
    });
}

}  // namespace mocapdb::cli
