// mocapdb eval: builds the evaluation sets from the CMU clips, runs every experiment of issue #7
// (leave-one-out prediction, constraint accuracy, reliability against error, sample reduction, foot
// skating, compression, runtime) and writes eval/REPORT.md with its figures and the numbers as CSV and
// JSON (eval_report.hpp).
#include <sys/resource.h>
#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

#include "commands.hpp"
#include "eval_report.hpp"
#include "mocapdb/core/error.hpp"
#include "progress_bar.hpp"

namespace mocapdb::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct EvalArgs {
    std::string data;
    std::string out;
    bool quick = false;
    bool tiny = false;
    std::string command;
};

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::vector<std::string> clip_range(const std::string& subject, int first, int last, const std::vector<int>& skip = {}) {
    std::vector<std::string> out;
    for (int t = first; t <= last; ++t) {
        if (std::find(skip.begin(), skip.end(), t) != skip.end()) continue;
        out.push_back(subject + "_" + (t < 10 ? "0" : "") + std::to_string(t));
    }
    return out;
}

// What one run does (full / quick / tiny).
struct Plan {
    struct SetPlan {
        eval::EvalSetSpec spec;
        bool loo = true;
        Eigen::Index loo_stride = 1;   // leave out every k-th sample
        bool constraint = true;
        bool reduction = false;
        bool compression = true;
    };
    std::vector<SetPlan> sets;
    std::vector<double> tucker_targets = {1.0, 3.0};
    eval::ConstraintOptions constraint;
    eval::ReductionCurveOptions reduction;
    std::vector<double> compression_targets = {5.0, 2.0, 1.0, 0.5};
    bool hooi = true;
    std::vector<std::string> hooi_sets;  // when not empty: HOOI rows only for these sets
    std::string runtime_set;
    eval::RuntimeOptions runtime;
};

eval::EvalSetSpec walks_spec(Eigen::Index frames) {
    eval::EvalSetSpec s;
    s.name = "walks16";
    s.description = "subject 16 walks: straight, veering and 90-degree turns at two speeds, plus slow walks (speed x turn grid)";
    s.clips = clip_range("16", 11, 34);
    s.clips.push_back("16_47");
    s.gait_cycles = true;  // phase-consistent samples: one gait cycle per clip
    s.max_cycles_per_clip = 1;
    s.extractors = {"turn", "speed"};
    s.frames = frames;
    return s;
}

Plan make_plan(const EvalArgs& a) {
    Plan p;
    if (a.tiny) {
        eval::EvalSetSpec s = walks_spec(12);
        s.clips = {"16_11", "16_13", "16_15", "16_17", "16_19", "16_21", "16_23", "16_25", "16_31"};
        p.sets.push_back({s, true, 3, true, true, true});
        p.constraint.points_per_axis_2d = 3;
        p.reduction.checkpoints = 2;
        p.reduction.random_orders = 1;
        p.compression_targets = {5.0};
        p.hooi = false;
        p.runtime_set = s.name;
        p.runtime.sizes = {5, 9};
        p.runtime.repeats = 1;
        return p;
    }
    if (a.quick) {
        p.sets.push_back({walks_spec(30), true, 3, true, true, true});
        p.constraint.points_per_axis_2d = 6;
        p.reduction.checkpoints = 4;
        p.reduction.random_orders = 2;
        p.compression_targets = {2.0, 1.0};
        p.hooi = false;
        p.runtime_set = "walks16";
        p.runtime.sizes = {8, 16, 25};
        p.runtime.repeats = 1;
        return p;
    }
    p.sets.push_back({walks_spec(40), true, 1, true, false, true});
    {
        eval::EvalSetSpec s;
        s.name = "runs16";
        s.description = "subject 16 runs/jogs: straight, veering and 90-degree turns (speed x turn grid)";
        s.clips = clip_range("16", 36, 56, {47});
        s.gait_cycles = true;
        s.max_cycles_per_clip = 1;
        s.extractors = {"turn", "speed"};
        s.frames = 40;
        p.sets.push_back({s, true, 1, true, false, true});
    }
    {
        eval::EvalSetSpec s;
        s.name = "jumps";
        s.description = "forward jumps of subjects 13, 16 and 105, parameterized by jump length";
        s.clips = {"13_11", "13_13", "13_19", "13_32"};
        for (const auto& c : clip_range("16", 5, 10, {8})) s.clips.push_back(c);
        for (const auto& c : clip_range("105", 39, 45)) s.clips.push_back(c);
        s.extractors = {"jump"};
        s.frames = 40;
        p.sets.push_back({s, true, 1, true, false, true});
    }
    {
        eval::EvalSetSpec s;
        s.name = "jumpturns105";
        s.description = "subject 105 jump turns (90 to 360 degrees, both directions), parameterized by turn angle";
        s.clips = clip_range("105", 46, 61, {57});
        s.extractors = {"turn"};
        s.frames = 40;
        p.sets.push_back({s, true, 1, true, false, true});
    }
    {
        eval::EvalSetSpec s;
        s.name = "gait105";
        s.description = "gait cycles segmented from subject 105's long styled walks (many samples from few clips)";
        s.clips = {"105_11", "105_13", "105_17", "105_19", "105_22", "105_29", "105_33"};
        s.gait_cycles = true;
        s.max_cycles_per_clip = 10;
        s.extractors = {"speed", "turn"};
        s.frames = 40;
        p.sets.push_back({s, true, 2, true, true, true});
    }
    p.constraint.points_per_axis_2d = 12;
    p.constraint.points_1d = 40;
    p.runtime_set = "gait105";
    p.runtime.sizes = {8, 16, 32, 60};
    p.runtime.repeats = 2;
    p.compression_targets = {2.0, 1.0, 0.5};
    p.hooi_sets = {"walks16"};
    return p;
}

std::vector<eval::MethodSpec> methods_for(const eval::EvalSet& set, const Plan& plan, std::vector<double>& targets) {
    using eval::MethodKind;
    std::vector<eval::MethodSpec> m;
    m.push_back({MethodKind::PerPoseKriging, "per-pose kriging", {0, 0, 0}, {}});
    m.push_back({MethodKind::PerElementKriging, "per-element kriging", {0, 0, 0}, {}});
    for (double t : plan.tucker_targets) {
        std::ostringstream name;
        name << "tucker-" << t << "cm";
        m.push_back({MethodKind::TuckerKriging, name.str(), eval::ranks_for_max_error(set, t), {}});
        targets.push_back(t);
    }
    // The error targets above keep every sample direction on these sets; a truncated sample mode
    // (a third of the samples, the loosest target's dof and time ranks) shows what compressing it costs.
    if (!plan.tucker_targets.empty() && set.size() >= 6) {
        const double loosest = *std::max_element(plan.tucker_targets.begin(), plan.tucker_targets.end());
        tensor::Ranks ranks = eval::ranks_for_max_error(set, loosest);
        ranks[2] = std::min<Eigen::Index>(ranks[2], (set.size() + 2) / 3);
        m.push_back({MethodKind::TuckerKriging, "tucker-R3=N/3", ranks, {}});
        targets.push_back(loosest);
    }
    m.push_back({MethodKind::NaiveKriging, "naive kriging", {0, 0, 0}, {}});
    m.push_back({MethodKind::Rbf, "rbf", {0, 0, 0}, {}});
    m.push_back({MethodKind::NearestNeighbour, "nn-blend k=3", {0, 0, 0}, {}});
    m.push_back({MethodKind::TrendOnly, "trend only", {0, 0, 0}, {}});
    return m;
}

std::string first_line(const std::string& path, const std::string& key) {
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line))
        if (key.empty() || line.rfind(key, 0) == 0) {
            const auto colon = line.find(':');
            return key.empty() || colon == std::string::npos ? line : line.substr(colon + 2);
        }
    return "unknown";
}

RunInfo run_info(const EvalArgs& a) {
    RunInfo info;
    info.command = a.command;
    info.mode = a.tiny ? "tiny" : a.quick ? "quick" : "full";
    const std::time_t now = std::time(nullptr);
    char buf[64];
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
    info.date = buf;
    utsname u{};
    std::string uname = "unknown";
    if (::uname(&u) == 0) uname = std::string(u.sysname) + " " + u.release + " " + u.machine;
    info.machine = uname + ", " + std::to_string(std::thread::hardware_concurrency()) + " cores, " +
                   first_line("/proc/cpuinfo", "model name");
    info.load = first_line("/proc/loadavg", "");
    std::string build;
#if defined(__clang__)
    build = "clang " __clang_version__;
#elif defined(__GNUC__)
    build = "gcc " __VERSION__;
#endif
#if defined(__OPTIMIZE__)
    build += ", optimized";
#else
    build += ", NOT optimized (debug build: timings are not representative)";
#endif
#if defined(NDEBUG)
    build += ", NDEBUG (Release)";
#else
    build += ", assertions on";
#endif
#if defined(__SANITIZE_ADDRESS__)
    build += ", AddressSanitizer";
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    build += ", AddressSanitizer";
#endif
#endif
    info.build = build;
    return info;
}

void say(const char* format, ...) __attribute__((format(printf, 1, 2)));
void say(const char* format, ...) {
    va_list args;
    va_start(args, format);
    std::vprintf(format, args);
    va_end(args);
    std::fflush(stdout);
}

void run_eval(const EvalArgs& a) {
    const auto start = Clock::now();
    const std::filesystem::path cmu = std::filesystem::path(a.data) / "cmu-asfamc";
    if (!std::filesystem::is_directory(cmu))
        throw InvalidArgument("--data " + a.data + ": no folder cmu-asfamc inside (expected the shared datasets folder)");
    const Plan plan = make_plan(a);
    EvalResults results;
    results.info = run_info(a);
    std::vector<eval::EvalSet> sets;
    std::vector<double> build_seconds;
    for (const Plan::SetPlan& sp : plan.sets) {
        const auto t0 = Clock::now();
        sets.push_back(eval::build_eval_set(sp.spec, cmu));
        build_seconds.push_back(since(t0));
        say("[eval] set %s: %lld samples, %lld dofs x %lld frames (%.1f s)\n", sp.spec.name.c_str(),
            static_cast<long long>(sets.back().size()), static_cast<long long>(sets.back().aligned.dofs()),
            static_cast<long long>(sets.back().aligned.frames()), build_seconds.back());
    }
    for (std::size_t k = 0; k < sets.size(); ++k) {
        const eval::EvalSet& set = sets[k];
        const Plan::SetPlan& sp = plan.sets[k];
        SetResults r;
        r.set = &set;
        r.build_seconds = build_seconds[k];
        r.methods = methods_for(set, plan, r.tucker_targets_cm);
        if (sp.loo) {
            const auto t0 = Clock::now();
            eval::LooOptions lo;
            for (Eigen::Index i = 0; i < set.size(); i += sp.loo_stride) lo.samples.push_back(i);
            {
                ProgressBar bar("eval " + set.spec.name + ": leave-one-out");
                r.loo = eval::leave_one_out(set, r.methods, lo, bar.callback());
            }
            r.has_loo = true;
            r.loo_seconds = since(t0);
            say("[eval] %s: leave-one-out over %zu samples x %zu methods (%.1f s)\n", set.spec.name.c_str(),
                lo.samples.size(), r.methods.size(), r.loo_seconds);
        }
        if (sp.constraint) {
            const auto t0 = Clock::now();
            r.constraint_options = plan.constraint;
            {
                ProgressBar bar("eval " + set.spec.name + ": constraints");
                r.constraint = eval::constraint_accuracy(set, r.methods, plan.constraint, bar.callback());
            }
            r.has_constraint = true;
            say("[eval] %s: constraint accuracy on %lld grid points (%.1f s)\n", set.spec.name.c_str(),
                static_cast<long long>(r.constraint.grid.rows()), since(t0));
        }
        if (sp.reduction) {
            const auto t0 = Clock::now();
            r.reduction_options = plan.reduction;
            {
                ProgressBar bar("eval " + set.spec.name + ": reduction");
                r.reduction = eval::reduction_curve(set, plan.reduction, bar.callback());
            }
            r.has_reduction = true;
            say("[eval] %s: sample reduction, %lld of %lld kept at tau %.2f (%.1f s)\n", set.spec.name.c_str(),
                static_cast<long long>(r.reduction.kept_at_tau), static_cast<long long>(set.size()), plan.reduction.tau,
                since(t0));
        }
        if (sp.compression) {
            const auto t0 = Clock::now();
            compression::RateOptions ro;
            ro.max_cm = plan.compression_targets;
            ro.parameters = set.set.parameters.cols();
            ro.hooi = plan.hooi && (plan.hooi_sets.empty() || std::find(plan.hooi_sets.begin(), plan.hooi_sets.end(),
                                                                                      set.spec.name) != plan.hooi_sets.end());
            r.compression_targets = plan.compression_targets;
            {
                ProgressBar bar("eval " + set.spec.name + ": compression");
                ro.progress = bar.callback();
                r.compression = compression::rate_distortion(set.aligned.tensor, set.skeleton, ro);
            }
            r.has_compression = true;
            say("[eval] %s: compression report (%.1f s)\n", set.spec.name.c_str(), since(t0));
        }
        results.sets.push_back(std::move(r));
    }
    for (std::size_t k = 0; k < sets.size(); ++k) {
        if (sets[k].spec.name != plan.runtime_set) continue;
        const auto t0 = Clock::now();
        eval::RuntimeOptions ro = plan.runtime;
        for (Eigen::Index& s : ro.sizes) s = std::min(s, sets[k].size());
        ro.sizes.erase(std::unique(ro.sizes.begin(), ro.sizes.end()), ro.sizes.end());
        {
            ProgressBar bar("eval: runtime");
            results.runtime = eval::runtime_scaling(sets[k], results.sets[k].methods, ro, bar.callback());
        }
        results.runtime_set = plan.runtime_set;
        say("[eval] runtime against N on %s (%.1f s)\n", plan.runtime_set.c_str(), since(t0));
    }
    results.info.wall_seconds = since(start);
    rusage usage{};
    if (::getrusage(RUSAGE_SELF, &usage) == 0)
        results.info.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                                   1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    write_eval_report(results, a.out);
    say("[eval] wrote %s (%.1f s in all)\n", (std::filesystem::path(a.out) / "REPORT.md").string().c_str(), since(start));
}

}  // namespace

void setup_eval(CLI::App& app) {
    auto a = std::make_shared<EvalArgs>();
    CLI::App* cmd = app.add_subcommand("eval", "Evaluate the interpolators and compressors against the baselines (REPORT.md)");
    cmd->footer(
        "Examples:\n"
        "  mocapdb eval --data ../shared/datasets --out eval/\n"
        "  mocapdb eval --data ../shared/datasets --out /tmp/eval --quick\n"
        "Builds the evaluation sets from DATA/cmu-asfamc in memory (subject 16 walks and runs, forward jumps\n"
        "of subjects 13/16/105, subject 105 jump turns and gait cycles), runs leave-one-out prediction,\n"
        "constraint accuracy, reliability against error, sample reduction, foot skating, compression and\n"
        "runtime for per-pose / per-element / Tucker / naive kriging, RBF and a nearest-neighbour blend, and\n"
        "writes OUT/REPORT.md, OUT/results.json and CSV and SVG files (replacing those of a previous run).\n"
        "--quick: subject 16 walks only, fewer leave-one-out folds and grid points (every section present).");
    cmd->add_option("--data", a->data, "the shared datasets folder (holding cmu-asfamc/)")->required();
    cmd->add_option("--out", a->out, "output folder for REPORT.md, results.json, CSV and SVG")->required();
    cmd->add_flag("--quick", a->quick, "a reduced run (subject 16 walks only) for smoke tests");
    cmd->add_flag("--tiny", a->tiny, "")->group("");  // hidden: smallest run, for sanitizer builds
    cmd->callback([a, cmd] {
        EvalArgs args = *a;
        args.command = "mocapdb eval --data " + a->data + " --out " + a->out + (a->quick ? " --quick" : "") +
                       (a->tiny ? " --tiny" : "");
        (void)cmd;
        run_eval(args);
    });
}

}  // namespace mocapdb::cli
