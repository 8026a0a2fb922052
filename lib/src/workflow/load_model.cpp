#include "mocapdb/workflow/load_model.hpp"

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::workflow {
namespace {

// What every synthesis model needs from the database: the set, its aligned form, its skeleton and
// frame rate (those of the first sample's clip).
struct AlignedSetData {
    MotionSet set;
    AlignedSet aligned;
    std::shared_ptr<const Skeleton> skeleton;
    double frame_rate = 0.0;
};

AlignedSetData load_aligned_set(const Database& db, const std::string& name) {
    AlignedSetData d;
    d.set = db.load_set(name);
    auto aligned = db.load_aligned(name);
    if (!aligned)
        throw InvalidArgument("set '" + name + "' in " + db.path().string() + " is not aligned (run: mocapdb align " +
                              db.path().string() + " --set " + name + ")");
    d.aligned = std::move(*aligned);
    const auto record = db.find_clip(d.set.samples.front().clip);
    if (!record) throw InvalidArgument("set '" + name + "': clip '" + d.set.samples.front().clip + "' is missing");
    d.skeleton = db.load_skeleton(record->skeleton);
    d.frame_rate = record->frame_rate;
    return d;
}

}  // namespace

std::unique_ptr<synthesis::MotionModel> load_motion_model(const Database& db, const std::string& name,
                                                          const synthesis::SynthesisOptions& options) {
    AlignedSetData d = load_aligned_set(db, name);
    const auto stored = db.load_model(name);
    if (!stored)
        throw InvalidArgument("set '" + name + "' in " + db.path().string() +
                              " has no compressed model (run: mocapdb compress " + db.path().string() + " --set " +
                              name + ")");
    synthesis::SynthesisOptions with_fit = options;
    if (!with_fit.kernel_fit) with_fit.kernel_fit = db.load_kernel_fit(name);  // nullopt for models stored without one
    return std::make_unique<synthesis::MotionModel>(stored->model, d.aligned, d.set, std::move(d.skeleton), d.frame_rate,
                                                    with_fit);
}

std::unique_ptr<synthesis::NaiveMotionModel> load_naive_motion_model(const Database& db, const std::string& name,
                                                                     const synthesis::SynthesisOptions& options) {
    AlignedSetData d = load_aligned_set(db, name);
    const VecX weight = compression::position_error_weights(*d.skeleton);
    return std::make_unique<synthesis::NaiveMotionModel>(d.aligned, d.set, std::move(d.skeleton), d.frame_rate, weight,
                                                         options);
}

}  // namespace mocapdb::workflow
