#include "mocapdb/core/stopwatch.hpp"
#include "mocapdb/packing/measured_pack.hpp"

#include <algorithm>
#include <chrono>
#include <string>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/parallel_tasks.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/group_decoder.hpp"

namespace mocapdb::packing {

MeasuredGroup pack_measured(const std::vector<const Clip*>& clips, const PackOptions& options,
                            const std::vector<MatX>& source_positions, const ProgressCallback& progress) {
    if (!source_positions.empty() && source_positions.size() != clips.size())
        throw InvalidArgument("pack_measured: " + std::to_string(source_positions.size()) +
                              " source position matrices for " + std::to_string(clips.size()) + " clips");
    const double E = options.max_error_cm;
    PackOptions attempt_options = options;
    MeasuredGroup out;
    for (int attempt = 0;; ++attempt) {
        const auto t_pack = std::chrono::steady_clock::now();
        out.packed = pack_group(clips, attempt_options, progress);  // validates E, W, threads
        out.encode_seconds += seconds_since(t_pack);
        out.attempts = attempt + 1;
        const GroupDecoder decoder(out.packed.bytes);
        // Clip by clip on the pack's threads, merged in clip order (the figures of one thread).
        std::vector<ErrorAccumulator> per_clip(clips.size(), ErrorAccumulator(E));
        std::vector<double> decode_seconds(clips.size(), 0.0);
        run_on_workers(static_cast<std::size_t>(std::max(1, options.threads)), clips.size(),
                       [&](std::size_t k, std::size_t) {
                           const auto t_decode = std::chrono::steady_clock::now();
                           const Clip decoded = decoder.decode_clip(k);
                           decode_seconds[k] = seconds_since(t_decode);
                           if (source_positions.empty())
                               add_position_errors(joint_positions(*clips[k]), joint_positions(decoded), per_clip[k]);
                           else add_position_errors(source_positions[k], joint_positions(decoded), per_clip[k]);
                       });
        out.clip_errors.clear();
        out.errors = ErrorAccumulator(E);
        out.decode_seconds = 0.0;
        for (std::size_t k = 0; k < clips.size(); ++k) {
            out.clip_errors.push_back(per_clip[k].stats());
            out.errors.merge(per_clip[k]);
            out.decode_seconds += decode_seconds[k];
        }
        const double excess = out.errors.stats().max_cm - E;
        if (!(excess > 0.0)) return out;
        if (attempt == 2)
            throw Error("pack: the decoded group of '" + clips.front()->name + "' misses the bound by " +
                        std::to_string(excess) + " cm after 3 attempts");
        attempt_options.max_error_cm -= 2.0 * excess + 1e-9 * E;
    }
}

}  // namespace mocapdb::packing
