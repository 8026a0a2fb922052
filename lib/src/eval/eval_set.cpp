#include "mocapdb/eval/eval_set.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/dataset/dropout_repair.hpp"
#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/io/clip_file.hpp"

namespace mocapdb::eval {
namespace {

void check_compatible(const Skeleton& a, const Skeleton& b, const std::string& what) {
    bool same = a.size() == b.size() && a.channel_count() == b.channel_count();
    for (std::size_t j = 0; same && j < a.size(); ++j) {
        same = a.joint(j).name == b.joint(j).name && a.joint(j).channels == b.joint(j).channels &&
               a.joint(j).parent == b.joint(j).parent;
    }
    if (!same)
        throw InvalidArgument("build_eval_set: " + what +
                              ": its skeleton's joints or channels differ from the set's first skeleton");
}

}  // namespace

EvalSet build_eval_set(const EvalSetSpec& spec, const std::filesystem::path& cmu_dir) {
    if (spec.clips.empty()) throw InvalidArgument("build_eval_set: set '" + spec.name + "' lists no clips");
    if (spec.frames < 2)
        throw InvalidArgument("build_eval_set: set '" + spec.name + "' needs at least 2 aligned frames");
    EvalSet out;
    out.spec = spec;
    out.set.name = spec.name;
    for (const std::string& e : spec.extractors) out.extractors.push_back(ParameterExtractor::parse(e));
    for (const ParameterExtractor& e : out.extractors) {
        for (const std::string& n : e.names()) out.set.parameter_names.push_back(n);
        for (const std::string& u : e.units()) out.set.parameter_units.push_back(u);
    }
    out.set.dropouts_checked = true;
    out.set.parameter_source = "extract:";
    for (std::size_t k = 0; k < spec.extractors.size(); ++k)
        out.set.parameter_source += (k ? "," : "") + spec.extractors[k];
    std::vector<VecX> rows;
    for (const std::string& id : spec.clips) {
        const std::filesystem::path path = cmu_dir / (id + ".amc");
        Clip clip = read_clip(path);
        // Solver dropouts repaired before segmentation and measurement, as set building does; the
        // runs are kept in set.repairs so that reports can name them.
        const std::vector<DropoutRun> dropouts = detect_dropouts(clip);
        repair_dropouts(clip, dropouts);
        if (!out.skeleton) {
            out.skeleton = clip.skeleton;
            out.frame_rate = clip.frame_rate;
            out.skeleton_source = id.substr(0, id.find('_')) + ".asf";
        } else {
            check_compatible(*out.skeleton, *clip.skeleton, path.string());
        }
        std::vector<SampleRef> refs;
        if (spec.gait_cycles) {
            GaitCycleOptions gait;
            gait.max_per_clip = spec.max_cycles_per_clip;
            refs = gait_cycles(clip, id, gait);
        } else if (spec.flight_windows) {
            refs = flight_window(clip, id);
        } else {
            refs.push_back({id, 0, clip.frame_count()});
        }
        if (refs.empty()) {
            out.skipped.push_back(id);
            continue;
        }
        out.clip_ids.push_back(id);
        for (RepairedFrames& r : repair_records(id, dropouts)) out.set.repairs.push_back(std::move(r));
        for (const SampleRef& r : refs) {
            rows.push_back(extract_parameters(clip, r.begin, r.end, out.extractors));
            Clip s = slice(clip, r.begin, r.end);
            s.skeleton = out.skeleton;  // replayed on the set's skeleton (see the header)
            s.name = sample_label(r, clip.frame_count());
            out.labels.push_back(s.name);
            out.samples.push_back(std::move(s));
            out.set.samples.push_back(r);
        }
    }
    if (out.samples.size() < 3)
        throw InvalidArgument("build_eval_set: set '" + spec.name + "' has " + std::to_string(out.samples.size()) +
                              " samples; at least 3 are needed");
    out.set.parameters.resize(static_cast<Eigen::Index>(rows.size()),
                              static_cast<Eigen::Index>(out.set.parameter_names.size()));
    for (std::size_t i = 0; i < rows.size(); ++i)
        out.set.parameters.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
    validate(out.set);
    AlignOptions ao;
    ao.method = "dtw";
    ao.frames = spec.frames;
    // The first frame's heading, not the travel frame (align's default): with travel-framed walks the
    // per-pose kriging no longer reproduces a training sample exactly (1.6 cm at 16_15 in
    // test_eval_blocks), a fragility of its per-frame kernels to fix before the
    // evaluation switches.
    ao.canonical = "first-frame";
    out.aligned = align_samples(out.samples, ao);
    return out;
}

EvalSet subset(const EvalSet& set, const std::vector<Eigen::Index>& keep) {
    const Eigen::Index n = set.size();
    std::vector<bool> seen(static_cast<std::size_t>(n), false);
    for (Eigen::Index k : keep) {
        if (k < 0 || k >= n || seen[static_cast<std::size_t>(k)])
            throw InvalidArgument("eval::subset: index " + std::to_string(k) +
                                  " is out of range or repeated (N = " + std::to_string(n) + ")");
        seen[static_cast<std::size_t>(k)] = true;
    }
    if (keep.empty()) throw InvalidArgument("eval::subset: no sample kept");
    EvalSet out;
    out.spec = set.spec;
    out.skeleton = set.skeleton;
    out.skeleton_source = set.skeleton_source;
    out.extractors = set.extractors;
    out.frame_rate = set.frame_rate;
    out.clip_ids = set.clip_ids;
    out.set.name = set.set.name;
    out.set.parameter_names = set.set.parameter_names;
    out.set.parameter_units = set.set.parameter_units;
    out.set.parameter_source = set.set.parameter_source;
    out.set.parameter_periods = set.set.parameter_periods;  // periodic axes stay periodic in every fold
    out.set.parameter_levels = set.set.parameter_levels;    // and categorical ones categorical
    out.set.dropouts_checked = set.set.dropouts_checked;
    out.set.repairs = set.set.repairs;  // samples keep their repaired frames
    const Eigen::Index m = static_cast<Eigen::Index>(keep.size());
    out.set.parameters.resize(m, set.set.parameters.cols());
    const AlignedSet& a = set.aligned;
    out.aligned.method = a.method;
    out.aligned.reference = 0;
    out.aligned.mean = a.mean;
    out.aligned.scale = a.scale;
    out.aligned.warps.resize(a.frames(), m);
    out.aligned.tensor.resize(a.dofs(), a.frames(), m);
    for (Eigen::Index j = 0; j < m; ++j) {
        const Eigen::Index i = keep[static_cast<std::size_t>(j)];
        const auto si = static_cast<std::size_t>(i);
        out.samples.push_back(set.samples[si]);
        out.labels.push_back(set.labels[si]);
        out.set.samples.push_back(set.set.samples[si]);
        out.set.parameters.row(j) = set.set.parameters.row(i);
        out.aligned.warps.col(j) = a.warps.col(i);
        out.aligned.canonical.push_back(a.canonical[si]);
        if (i == static_cast<Eigen::Index>(a.reference)) out.aligned.reference = static_cast<std::size_t>(j);
        std::copy(a.tensor.data() + i * a.dofs() * a.frames(), a.tensor.data() + (i + 1) * a.dofs() * a.frames(),
                  out.aligned.tensor.data() + j * a.dofs() * a.frames());
    }
    return out;
}

}  // namespace mocapdb::eval
