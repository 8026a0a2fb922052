#include "mocapdb/workflow/set_reduction.hpp"

#include <algorithm>
#include <optional>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/load_model.hpp"

namespace mocapdb::workflow {

ReductionOutcome reduce_set(const std::filesystem::path& db_path, const ReductionRequest& request) {
    const Database db(db_path);
    ReductionOutcome out;
    out.set = db.load_set(request.set);
    std::unique_ptr<synthesis::SynthesisModel> model;
    if (request.naive) model = load_naive_motion_model(db, request.set);
    else model = load_motion_model(db, request.set);
    const MatX xc = model->scaling().apply(model->sample_parameters());
    kriging::ReductionOptions options;
    options.tau = request.tau;
    options.min_samples = request.min_samples;
    options.kriging = model->kriging_options();
    out.result = kriging::reduce_samples(xc, model->report().model, options);
    out.model_kind = model->kind();
    out.kernel = model->report().model;
    for (const SampleRef& s : out.set.samples) {
        const auto rec = db.find_clip(s.clip);
        out.labels.push_back(sample_label(s, rec ? rec->frames : s.end));
    }
    return out;
}

MotionSet reduced_set(const MotionSet& set, const std::vector<Eigen::Index>& kept, const std::string& name) {
    MotionSet reduced = set;
    reduced.name = name;
    reduced.samples.clear();
    reduced.parameters.resize(static_cast<Eigen::Index>(kept.size()), set.parameters.cols());
    for (std::size_t k = 0; k < kept.size(); ++k) {
        reduced.samples.push_back(set.samples[static_cast<std::size_t>(kept[k])]);
        reduced.parameters.row(static_cast<Eigen::Index>(k)) = set.parameters.row(kept[k]);
    }
    // Repair records only of the clips the reduced set still uses.
    reduced.repairs.clear();
    for (const RepairedFrames& x : set.repairs)
        if (std::any_of(reduced.samples.begin(), reduced.samples.end(),
                        [&](const SampleRef& s) { return s.clip == x.clip; }))
            reduced.repairs.push_back(x);
    // parameter_source keeps saying how the values were obtained (synth re-measures with it).
    return reduced;
}

bool store_reduced_set(const std::filesystem::path& db_path, const ReductionOutcome& outcome, const std::string& name,
                       bool replace) {
    const std::vector<Eigen::Index>& kept = outcome.result.kept;
    if (kept.size() < 2)
        throw InvalidArgument("reduced set '" + name + "': " + std::to_string(kept.size()) +
                              " kept samples, at least 2 needed");
    const MotionSet reduced = reduced_set(outcome.set, kept, name);
    // Align like the original (method and frames; the reference is the reduced set's median sample).
    std::optional<AlignedSet> aligned;
    {
        const Database db(db_path);  // closed before the commit (an open reader keeps replaced segments)
        const auto original = db.load_aligned(outcome.set.name);
        if (original) {
            std::vector<Clip> clips;
            for (std::size_t k = 0; k < reduced.samples.size(); ++k)
                clips.push_back(sample_frames(reduced, k, db.load_clip(reduced.samples[k].clip)));
            AlignOptions ao;
            ao.method = original->method;
            ao.frames = original->frames();
            aligned = align_samples(clips, ao);
        }
    }
    DatabaseWriter writer(db_path, DatabaseWriter::Mode::OpenOrCreate);
    if (writer.view().has_set(name) && !replace)
        throw InvalidArgument(db_path.string() + ": set '" + name + "' exists (replace it, or choose another name)");
    writer.put_set(reduced, replace);
    if (aligned) writer.put_aligned(name, *aligned);
    writer.commit();
    return aligned.has_value();
}

}  // namespace mocapdb::workflow
