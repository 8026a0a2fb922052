#include "mocapdb/eval/runtime_scaling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "mocapdb/core/error.hpp"

namespace mocapdb::eval {
namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

std::vector<RuntimeRow> runtime_scaling(const EvalSet& set, const std::vector<MethodSpec>& methods,
                                        const RuntimeOptions& options, const ProgressCallback& progress) {
    const Eigen::Index n = set.size();
    if (options.repeats < 1) throw InvalidArgument("runtime_scaling: repeats must be >= 1");
    std::vector<Eigen::Index> sizes = options.sizes;
    if (sizes.empty()) {
        for (Eigen::Index s = 8; s < n; s *= 2) sizes.push_back(s);
        sizes.push_back(n);
    }
    for (Eigen::Index s : sizes)
        if (s < 3 || s > n) throw InvalidArgument("runtime_scaling: sizes must be in 3 .. N = " + std::to_string(n));
    std::vector<RuntimeRow> out;
    std::uint64_t done = 0;
    const Eigen::Index frames = set.aligned.frames();
    for (Eigen::Index s : sizes) {
        // Evenly spread samples, so small sets still cover the parameter range.
        std::vector<Eigen::Index> keep;
        for (Eigen::Index k = 0; k < s; ++k) {
            const Eigen::Index i =
                s == 1 ? 0
                       : static_cast<Eigen::Index>(std::lround(static_cast<double>(k) * static_cast<double>(n - 1) /
                                                               static_cast<double>(s - 1)));
            if (keep.empty() || keep.back() != i) keep.push_back(i);
        }
        const EvalSet training = subset(set, keep);
        const Eigen::Index m = training.size();
        const VecX lo = training.set.parameters.colwise().minCoeff().transpose();
        const VecX hi = training.set.parameters.colwise().maxCoeff().transpose();
        for (const MethodSpec& spec : methods) {
            RuntimeRow row;
            row.method = spec.name;
            row.samples = m;
            row.frames = frames;
            std::vector<double> builds, queries;
            SynthesizedMotion motion;
            for (int r = 0; r < options.repeats; ++r) {
                const auto synth = build_synthesizer(spec, training);
                builds.push_back(synth->build_seconds);
                for (int q = 0; q < 5; ++q) {
                    const double f = (static_cast<double>(q + r * 5) + 0.5) / static_cast<double>(5 * options.repeats);
                    const VecX c = lo + f * (hi - lo);
                    const auto start = std::chrono::steady_clock::now();
                    synth->synthesize(c, motion);
                    queries.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
                }
            }
            row.build_seconds = median(builds);
            row.build_us_per_frame = 1e6 * row.build_seconds / static_cast<double>(m * frames);
            row.synth_us_per_frame = 1e6 * median(queries) / static_cast<double>(frames);
            out.push_back(row);
            if (progress) progress({++done, static_cast<std::uint64_t>(sizes.size() * methods.size()), spec.name});
        }
    }
    return out;
}

}  // namespace mocapdb::eval
