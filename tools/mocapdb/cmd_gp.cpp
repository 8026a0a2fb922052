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
#include "output_files.hpp"
#include "json_writer.hpp"
#include "progress_bar.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/core/keep_freed_memory.hpp"
#include "mocapdb/gp/child_selection.hpp"
#include "mocapdb/gp/experiment.hpp"
#include "mocapdb/gp/model_steps.hpp"
#include "mocapdb/gp/motion_data.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/workflow/gp_children.hpp"

namespace mocapdb::cli {
namespace {

namespace fs = std::filesystem;
using namespace mocapdb::gp;


struct GpArgs {
    // children
    std::string db;
    std::string set;
    std::vector<std::string> clips;
    double fps = 0.0;
    // data
    std::size_t frames = 90;
    double duration = 0.0;
    std::vector<std::string> joints;
    std::vector<std::string> exclude;
    bool keep_noisy = false;
    // model
    int layers = 2;
    std::vector<std::size_t> groups;
    std::string subject;
    std::size_t q = 1;
    std::size_t rank = 1;
    std::string kernel = "matern32";
    int restarts = 1;
    int max_iterations = 300;
    unsigned long long seed = 1;
    bool mo_baseline = false;
    bool json = false;
    // interpolate / sample / experiment
    std::string child;
    std::size_t observed = 40;
    std::size_t n = 10;
    std::string out;
    bool force = false;
    bool artificial = false;
    std::size_t runs = 5;
    std::vector<std::size_t> tests;
    std::vector<std::size_t> observed_list{40, 30, 20, 10};
    std::vector<std::string> eval_clips;
    std::size_t samples = 25;
};

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
    if (!a.exclude.empty()) o.exclude_joints = a.exclude == std::vector<std::string>{"none"} ? std::vector<std::string>{} : a.exclude;
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
const char* model_label(const GpArgs& a) { return a.mo_baseline ? "MOA" : a.layers == 3 ? "MOHGP (3 layers)" : "MOHGP"; }

void write_model(JsonWriter& w, const FitResult& f) {
    w.key("log_likelihood").value(f.log_likelihood);
    w.key("status").value(to_string(f.status));
    w.key("seconds").value(f.seconds);
    w.key("evaluations").value(f.evaluations);
    w.key("restarts").begin_array();
    for (const auto& r : f.restarts) {
        w.begin_object();
        w.key("log_likelihood").value(r.log_likelihood);
        w.key("status").value(to_string(r.status));
        w.key("message").value(r.message);
        w.key("iterations").value(r.iterations);
        w.key("evaluations").value(r.evaluations);
        w.key("seconds").value(r.seconds);
        w.end_object();
    }
    w.end_array();
    w.key("noise_variance").begin_array();
    const VecX noise = f.model.noise_variance();
    for (Eigen::Index i = 0; i < noise.size(); ++i) w.value(noise[i]);
    w.end_array();
    w.key("parameters").begin_object();
    const auto names = f.model.parameter_names();
    const VecX p = f.model.parameters();
    for (std::size_t i = 0; i < names.size(); ++i) w.key(names[i]).value(p[static_cast<Eigen::Index>(i)]);
    w.end_object();
}

void print_fit_summary(const char* label, const FitResult& f) {
    std::printf("%s: log likelihood %.4f, %s, %d evaluations, %.2f s\n", label, f.log_likelihood,
                to_string(f.status).c_str(), f.evaluations, f.seconds);
    const ModelSummary summary = summarize_model(f.model);
    auto terms = [](const char* layer, const std::vector<TermSummary>& layer_terms) {
        for (std::size_t q = 0; q < layer_terms.size(); ++q)
            std::printf("  %s q%zu: %s lengthscale %.4g s, mean B diagonal %.4g\n", layer, q,
                        to_string(layer_terms[q].kernel).c_str(), layer_terms[q].lengthscale_s, layer_terms[q].mean_b_diagonal);
    };
    terms("parent", summary.parent);
    terms("group ", summary.group);
    terms(f.model.hierarchical ? "child " : "MOA   ", summary.child);
    std::printf("  noise variance: mean %.3g (min %.3g, max %.3g)\n", summary.noise_mean, summary.noise_min, summary.noise_max);
}

void write_data_json(JsonWriter& w, const MotionData& md) {
    w.key("children").begin_array();
    for (const auto& n : md.child_names) w.value(n);
    w.end_array();
    if (!md.data.groups.empty()) {
        w.key("groups").begin_array();
        for (std::size_t g : md.data.groups) w.value(static_cast<long long>(g));
        w.end_array();
    }
    w.key("frames").value(static_cast<long long>(md.data.frames()));
    w.key("duration_s").value(md.data.times[md.data.times.size() - 1]);
    w.key("dofs").begin_array();
    for (const auto& n : md.dof_names) w.value(n);
    w.end_array();
}

void print_data_summary(const MotionData& md) {
    std::printf("children: %zu (", md.child_names.size());
    for (std::size_t i = 0; i < md.child_names.size(); ++i) std::printf("%s%s", i ? ", " : "", md.child_names[i].c_str());
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

void run_fit(const GpArgs& a) {
    const workflow::GpChildren children = load_children(a);
    MotionData md = prepare_motion_data(children.clips, children.names, data_options(a));
    assign_groups(a, md.child_names, md.data);
    ProgressBar bar("gp fit");
    const FitResult f = fit_model(md.data, model_spec(a, !a.mo_baseline), fit_options(a, &bar));
    bar.clear();
    if (a.json) {
        JsonWriter w;
        w.begin_object();
        w.key("model").value(model_name(a));
        write_data_json(w, md);
        write_model(w, f);
        w.end_object();
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
    const std::vector<bool>& mask = interpolation.observed;
    const InterpolationScores& s = interpolation.scores;
    const GaussianPrediction& p = interpolation.prediction;
    if (!a.out.empty()) write_bvh(fs::path(a.out), reassemble_clip(md, p.mean, md.child_names[child] + "-interpolated"));
    if (a.json) {
        JsonWriter w;
        w.begin_object();
        w.key("model").value(model_name(a));
        write_data_json(w, md);
        w.key("child").value(md.child_names[child]);
        w.key("observed_frames").begin_array();
        for (std::size_t i = 0; i < mask.size(); ++i)
            if (mask[i]) w.value(static_cast<long long>(i));
        w.end_array();
        w.key("mse").value(s.mse);
        w.key("smse").value(s.smse);
        w.key("msll").value(s.msll);
        w.key("predicted_values").value(static_cast<long long>(s.points));
        w.key("fit").begin_object();
        write_model(w, f);
        w.end_object();
        w.key("mean").begin_array();  // normalized units, D rows of T values
        for (Eigen::Index i = 0; i < p.mean.rows(); ++i) {
            w.begin_array();
            for (Eigen::Index t = 0; t < p.mean.cols(); ++t) w.value(p.mean(i, t));
            w.end_array();
        }
        w.end_array();
        w.end_object();
        std::cout << w.str();
        return;
    }
    print_data_summary(md);
    print_fit_summary(model_label(a), f);
    std::printf("child %s, %zu of %zu frames observed: MSE %.5f  SMSE %.4f  MSLL %.4f (%zu values predicted)\n",
                md.child_names[child].c_str(), a.observed, md.data.frames(), s.mse, s.smse, s.msll, s.points);
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
    const NewChildren drawn = sample_new_children(md.data, model_spec(a, !a.mo_baseline), fit_options(a, &bar), a.n, so);
    bar.clear();
    const FitResult& f = drawn.fit;
    const std::vector<MatX>& samples = drawn.samples;
    for (std::size_t i = 0; i < samples.size(); ++i)
        write_bvh(files[i], reassemble_clip(md, samples[i], files[i].stem().string()));
    write_bvh(files.back(), reassemble_clip(md, drawn.trend, "trend"));
    if (a.json) {
        JsonWriter w;
        w.begin_object();
        w.key("model").value(model_name(a));
        write_data_json(w, md);
        w.key("files").begin_array();
        for (const auto& p : files) w.value(p.string());
        w.end_array();
        w.key("fit").begin_object();
        write_model(w, f);
        w.end_object();
        w.end_object();
        std::cout << w.str();
        return;
    }
    print_data_summary(md);
    print_fit_summary(model_label(a), f);
    std::printf("wrote %zu samples and the trend to %s\n", samples.size(), dir.string().c_str());
}

void json_runs(JsonWriter& w, const ModelRuns& m) {
    w.begin_object();
    w.key("mse").begin_object().key("mean").value(m.mse.mean).key("std").value(m.mse.std).end_object();
    w.key("smse").begin_object().key("mean").value(m.smse.mean).key("std").value(m.smse.std).end_object();
    w.key("msll").begin_object().key("mean").value(m.msll.mean).key("std").value(m.msll.std).end_object();
    w.key("fit_seconds").value(m.fit_seconds);
    w.key("fit_status").begin_array();
    for (const auto& s : m.fit_status) w.value(s);
    w.end_array();
    w.end_object();
}

std::string pm(const MeanStd& m, int prec = 3) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f ± %.*f", prec, m.mean, prec, 2.0 * m.std);
    return b;
}

void json_synthesis(JsonWriter& w, const SynthesisScores& s) {
    w.begin_array();
    for (std::size_t i = 0; i < s.mcc.size(); ++i) {
        w.begin_object();
        w.key("mcc").begin_object().key("mean").value(s.mcc[i].mean).key("std").value(s.mcc[i].std).end_object();
        w.key("mlc").begin_object().key("mean").value(s.mlc[i].mean).key("std").value(s.mlc[i].std).end_object();
        w.end_object();
    }
    w.end_array();
}

void run_experiment_artificial(const GpArgs& a) {
    if (a.layers == 3)
        throw InvalidArgument("--artificial reproduces the thesis's two-layer experiment; --layers 3 needs real children "
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
        if (t < 1 || t > configs.size()) throw InvalidArgument("--tests: expected numbers 1.." + std::to_string(configs.size()));
        o.progress = bar.callback();
        results.push_back(run_artificial(configs[t - 1], o));
    }
    bar.clear();
    if (a.json) {
        JsonWriter w;
        w.begin_object();
        w.key("experiment").value("artificial");
        w.key("runs").value(static_cast<long long>(a.runs));
        w.key("q").value(static_cast<long long>(a.q));
        w.key("kernel").value(a.kernel);
        w.key("tests").begin_array();
        for (std::size_t i = 0; i < results.size(); ++i) {
            const auto& r = results[i];
            w.begin_object();
            w.key("test").value(static_cast<long long>(which[i]));
            w.key("noise").value(r.config.noise);
            w.key("outputs").value(static_cast<long long>(r.config.outputs));
            w.key("children").value(static_cast<long long>(r.config.children));
            w.key("mohgp");
            json_runs(w, r.mohgp);
            w.key("moa");
            json_runs(w, r.moa);
            w.end_object();
        }
        w.end_array();
        w.end_object();
        std::cout << w.str();
        return;
    }
    std::printf("artificial interpolation (thesis §5.1.1): %zu runs, 5 of 50 inputs observed on the test child, "
                "models LMC Q=%zu %s; mean ± 2 std over runs\n",
                a.runs, a.q, a.kernel.c_str());
    std::printf("%-5s %-6s %-5s %-6s | %-18s %-18s | %-18s %-18s | %-19s %-19s | fit s\n", "test", "noise", "D", "R",
                "MSE MOHGP", "MSE MOA", "SMSE MOHGP", "SMSE MOA", "MSLL MOHGP", "MSLL MOA");
    for (std::size_t i = 0; i < results.size(); ++i) {
        const auto& r = results[i];
        std::printf("%-5zu %-6g %-5zu %-6zu | %-18s %-18s | %-18s %-18s | %-19s %-19s | %.1f/%.1f\n", which[i], r.config.noise,
                    r.config.outputs, r.config.children, pm(r.mohgp.mse).c_str(), pm(r.moa.mse).c_str(),
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
        JsonWriter w;
        w.begin_object();
        w.key("experiment").value("replicates");
        w.key("layers").value(static_cast<long long>(a.layers));
        write_data_json(w, all);
        w.key("test_child").value(train_names[child]);
        w.key("mohgp_fit").begin_object();
        write_model(w, interp.mohgp_fit);
        w.end_object();
        w.key("moa_fit").begin_object();
        write_model(w, interp.moa_fit);
        w.end_object();
        w.key("interpolation").begin_array();
        for (const auto& row : interp.rows) {
            w.begin_object();
            w.key("observed").value(static_cast<long long>(row.observed));
            w.key("mohgp");
            json_runs(w, row.mohgp);
            w.key("moa");
            json_runs(w, row.moa);
            w.end_object();
        }
        w.end_array();
        if (do_synthesis) {
            w.key("synthesis").begin_object();
            w.key("samples").value(static_cast<long long>(a.samples));
            w.key("real").begin_array();
            for (std::size_t i = n_train; i < names.size(); ++i) w.value(names[i]);
            w.end_array();
            w.key("mohgp");
            json_synthesis(w, synth.mohgp);
            w.key("moa");
            json_synthesis(w, synth.moa);
            w.key("control");
            json_synthesis(w, synth.control);
            w.key("mohgp_fit_seconds").value(synth.mohgp_fit.seconds);
            w.key("moa_fit_seconds").value(synth.moa_fit.seconds);
            w.end_object();
        }
        w.end_object();
        std::cout << w.str();
        return;
    }
    print_data_summary(all);
    std::printf("test child %s; models trained on the other %zu children (LMC Q=%zu %s)\n", train_names[child].c_str(),
                n_train - 1, a.q, a.kernel.c_str());
    if (!data.groups.empty()) {
        std::printf("groups (three layers):");
        for (std::size_t r = 0; r < train_names.size(); ++r) std::printf(" %s=%zu", train_names[r].c_str(), data.groups[r]);
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
        std::printf("synthesis: %zu samples per model (trained on all %zu children), MCC / MLC mean ± 2 std per real motion;\n"
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

void add_source_options(CLI::App* cmd, GpArgs& a) {
    cmd->add_option("db", a.db, "database file (with --set)");
    cmd->add_option("--set", a.set, "motion set: its samples are the children");
    cmd->add_option("--clips", a.clips, "clip files (BVH, or AMC with the ASF beside it) as the children")->check(CLI::ExistingFile);
    cmd->add_option("--fps", a.fps, "frame rate override for the clip files (Hz)")->check(frame_rate_check());
    cmd->add_option("--frames", a.frames, "subsampled frames per child (default 90)")->check(CLI::Range(2, 100000));
    cmd->add_option("--duration", a.duration, "seconds from each child's start (default: the shortest child)");
    cmd->add_option("--joints", a.joints, "only these joints' dofs (names; the root name selects the 6 root dofs)")->delimiter(',');
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
    cmd->add_option("--groups", a.groups, "with --layers 3: one group index per child (0-based), e.g. 0,0,1,1")->delimiter(',');
    cmd->add_option("--q", a.q, "LMC terms per layer (default 1 = ICM)")->check(CLI::Range(1, 10));
    cmd->add_option("--rank", a.rank, "rank of every W_q (default 1)")->check(CLI::Range(1, 50));
    cmd->add_option("--kernel", a.kernel, "rbf | matern32 (default matern32)")->check(CLI::IsMember({"rbf", "matern32"}));
    cmd->add_option("--restarts", a.restarts, "optimizer restarts (deterministic; default 1)")->check(CLI::Range(1, 100));
    cmd->add_option("--max-iterations", a.max_iterations, "L-BFGS iterations per restart (default 300)")->check(CLI::Range(1, 100000));
    cmd->add_option("--seed", a.seed, "seed of restarts, observed frames and samples (default 1)");
    cmd->add_flag("--json", a.json, "machine-readable output on stdout");
}

}  // namespace

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
    fitc->footer("Example:\n  mocapdb gp fit db.h5 --set walks --q 1 --kernel matern32 --json\n"
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
    interp->footer("Example:\n  mocapdb gp interpolate --clips 02_01.amc 02_02.amc 35_01.amc --child 02_01 --observed 40\n"
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
    samp->add_option("--subject", a->subject,
                     "with --layers 3: new trials of this subject (e.g. 16; with --groups a group index) instead of a new subject");
    samp->add_option("-o,--output", a->out, "output folder (sample_001.bvh ..., trend.bvh)")->required();
    samp->add_flag("--force", a->force, "overwrite existing files");
    samp->footer("Example:\n  mocapdb gp sample db.h5 --set walks --n 5 -o samples/\n"
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
    exp->add_option("--tests", a->tests, "with --artificial: which of the 9 tests (1-based; default all)")->delimiter(',');
    exp->add_option("--runs", a->runs, "validation runs (default 5)")->check(CLI::Range(1, 1000));
    exp->add_option("--child", a->child, "test child for interpolation (name or index; default 0)");
    exp->add_option("--observed-list", a->observed_list, "observed frames per test (default 40,30,20,10)")->delimiter(',');
    exp->add_option("--eval-clips", a->eval_clips, "real motions to score synthesized samples against")->check(CLI::ExistingFile);
    exp->add_option("--samples", a->samples, "synthesized samples per model (default 25)");
    exp->footer("Examples:\n  mocapdb gp experiment --artificial --q 3 --kernel rbf --json\n"
                "  mocapdb gp experiment --clips 02_01.amc 02_02.amc 35_01.amc --child 02_01 --eval-clips 16_15.amc 16_16.amc\n"
                "Training uses the complete children; the test child's observed frames enter its posterior only.\n"
                "Tables print mean ± 2 std over the runs (the thesis's convention); JSON gives mean and std.");
    exp->callback([a] {
        keep_freed_memory();
        if (a->artificial)
            run_experiment_artificial(*a);
        else
            run_experiment_replicates(*a);
    });
}

}  // namespace mocapdb::cli
