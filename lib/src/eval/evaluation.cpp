#include "mocapdb/eval/evaluation.hpp"

#include <sys/resource.h>
#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <thread>

#include "mocapdb/core/error.hpp"

namespace mocapdb::eval {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

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

std::string build_description() {
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
    return build;
}

// Runs one stage between the observer's start and done calls.
template <typename Work>
void stage(const EvalObserver& observer, EvalStage kind, const EvalSet& set, const SetResults* results, Work work) {
    const auto t0 = Clock::now();
    {
        ProgressCallback progress =
            observer.stage_started ? observer.stage_started(kind, set.spec.name) : ProgressCallback{};
        work(progress);
    }
    if (observer.stage_done) observer.stage_done({kind, &set, results, since(t0)});
}

}  // namespace

RunInfo describe_run(const std::string& command, EvalMode mode) {
    RunInfo info;
    info.command = command;
    info.mode = to_string(mode);
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
    info.build = build_description();
    return info;
}

double process_cpu_seconds() {
    rusage usage{};
    if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
    return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

EvalResults run_evaluation(const EvalPlan& plan, const std::filesystem::path& cmu_dir, RunInfo info,
                           const EvalObserver& observer) {
    const auto start = Clock::now();
    if (!std::filesystem::is_directory(cmu_dir))
        throw InvalidArgument(cmu_dir.string() + ": not a folder (expected the CMU ASF/AMC clips)");
    EvalResults results;
    results.info = std::move(info);
    for (const EvalPlan::SetPlan& sp : plan.sets) {
        const auto t0 = Clock::now();
        auto set = std::make_shared<const EvalSet>(build_eval_set(sp.spec, cmu_dir));
        SetResults r;
        r.set = set;
        r.build_seconds = since(t0);
        results.sets.push_back(std::move(r));
        if (observer.stage_done)
            observer.stage_done({EvalStage::BuildSet, set.get(), nullptr, results.sets.back().build_seconds});
    }
    for (std::size_t k = 0; k < results.sets.size(); ++k) {
        SetResults& r = results.sets[k];
        const EvalSet& set = *r.set;
        const EvalPlan::SetPlan& sp = plan.sets[k];
        SetMethods methods = methods_for_set(set, plan.tucker_targets);
        r.methods = std::move(methods.methods);
        r.tucker_targets_cm = std::move(methods.tucker_targets_cm);
        if (sp.loo) {
            const auto t0 = Clock::now();
            LooOptions lo;
            for (Eigen::Index i = 0; i < set.size(); i += sp.loo_stride) lo.samples.push_back(i);
            {
                ProgressCallback progress = observer.stage_started
                                                ? observer.stage_started(EvalStage::LeaveOneOut, set.spec.name)
                                                : ProgressCallback{};
                r.loo = leave_one_out(set, r.methods, lo, progress);
            }
            r.has_loo = true;
            r.loo_seconds = since(t0);
            if (observer.stage_done) observer.stage_done({EvalStage::LeaveOneOut, &set, &r, r.loo_seconds});
            KernelHeadroomOptions ho = plan.headroom;
            ho.samples = lo.samples;
            stage(observer, EvalStage::KernelHeadroom, set, &r, [&](const ProgressCallback& progress) {
                r.headroom = kernel_headroom(set, ho, progress);
                r.has_headroom = true;
            });
            SetEvaluationOptions no;
            no.max_folds = lo.samples.size();
            no.learned_metric = true;
            if (set.size() >= 5)  // nested cross-validation needs 5 (smoke-test sets may have fewer)
                stage(observer, EvalStage::NestedChoice, set, &r, [&](const ProgressCallback& progress) {
                    r.nested = evaluate_set(set, set_methods({0, 0, 0}), no, progress);
                    r.has_nested = true;
                });
        }
        if (sp.constraint) {
            r.constraint_options = plan.constraint;
            stage(observer, EvalStage::Constraint, set, &r, [&](const ProgressCallback& progress) {
                r.constraint = constraint_accuracy(set, r.methods, plan.constraint, progress);
                r.has_constraint = true;
            });
            const auto tucker = std::find_if(r.methods.begin(), r.methods.end(),
                                             [](const MethodSpec& m) { return m.kind == MethodKind::TuckerKriging; });
            if (tucker != r.methods.end() && set.set.parameters.cols() > 0)
                stage(observer, EvalStage::EdgeWarning, set, &r, [&](const ProgressCallback&) {
                    r.edge = evaluate_edge_warning(set, tucker->ranks);
                    r.has_edge = true;
                });
        }
        if (sp.reduction) {
            r.reduction_options = plan.reduction;
            stage(observer, EvalStage::Reduction, set, &r, [&](const ProgressCallback& progress) {
                r.reduction = reduction_curve(set, plan.reduction, progress);
                r.has_reduction = true;
            });
        }
        if (sp.compression) {
            compression::RateOptions ro;
            ro.max_cm = plan.compression_targets;
            ro.parameters = set.set.parameters.cols();
            ro.hooi = plan.hooi && (plan.hooi_sets.empty() || std::find(plan.hooi_sets.begin(), plan.hooi_sets.end(),
                                                                        set.spec.name) != plan.hooi_sets.end());
            r.compression_targets = plan.compression_targets;
            stage(observer, EvalStage::Compression, set, &r, [&](const ProgressCallback& progress) {
                ro.progress = progress;
                r.compression = compression::rate_distortion(set.aligned.tensor, set.skeleton, ro);
                r.has_compression = true;
            });
        }
    }
    for (SetResults& r : results.sets) {
        const EvalSet& set = *r.set;
        if (set.spec.name != plan.runtime_set) continue;
        RuntimeOptions ro = plan.runtime;
        for (Eigen::Index& s : ro.sizes) s = std::min(s, set.size());
        ro.sizes.erase(std::unique(ro.sizes.begin(), ro.sizes.end()), ro.sizes.end());
        stage(observer, EvalStage::Runtime, set, nullptr, [&](const ProgressCallback& progress) {
            results.runtime = runtime_scaling(set, r.methods, ro, progress);
        });
        results.runtime_set = plan.runtime_set;
    }
    results.info.wall_seconds = since(start);
    results.info.cpu_seconds = process_cpu_seconds();
    return results;
}

}  // namespace mocapdb::eval
