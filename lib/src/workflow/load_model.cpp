#include "mocapdb/workflow/load_model.hpp"

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::workflow {

std::unique_ptr<synthesis::MotionModel> load_motion_model(const Database& db, const std::string& name,
                                               const synthesis::SynthesisOptions& options) {
    const MotionSet set = db.load_set(name);
    const auto aligned = db.load_aligned(name);
    if (!aligned)
        throw InvalidArgument("set '" + name + "' in " + db.path().string() + " is not aligned (run: mocapdb align " +
                              db.path().string() + " --set " + name + ")");
    const auto stored = db.load_model(name);
    if (!stored)
        throw InvalidArgument("set '" + name + "' in " + db.path().string() +
                              " has no compressed model (run: mocapdb compress " + db.path().string() + " --set " +
                              name + ")");
    const auto record = db.find_clip(set.samples.front().clip);
    if (!record) throw InvalidArgument("set '" + name + "': clip '" + set.samples.front().clip + "' is missing");
    if (!options.kernel_fit) {
        synthesis::SynthesisOptions with_fit = options;
        with_fit.kernel_fit = db.load_kernel_fit(name);  // nullopt for models stored without one
        return std::make_unique<synthesis::MotionModel>(stored->model, *aligned, set, db.load_skeleton(record->skeleton),
                                             record->frame_rate, with_fit);
    }
    return std::make_unique<synthesis::MotionModel>(stored->model, *aligned, set, db.load_skeleton(record->skeleton),
                                         record->frame_rate, options);
}

std::unique_ptr<synthesis::NaiveMotionModel> load_naive_motion_model(const Database& db, const std::string& name,
                                                          const synthesis::SynthesisOptions& options) {
    const MotionSet set = db.load_set(name);
    const auto aligned = db.load_aligned(name);
    if (!aligned)
        throw InvalidArgument("set '" + name + "' in " + db.path().string() + " is not aligned (run: mocapdb align " +
                              db.path().string() + " --set " + name + ")");
    const auto record = db.find_clip(set.samples.front().clip);
    if (!record) throw InvalidArgument("set '" + name + "': clip '" + set.samples.front().clip + "' is missing");
    auto skeleton = db.load_skeleton(record->skeleton);
    const VecX weight = compression::position_error_weights(*skeleton);
    return std::make_unique<synthesis::NaiveMotionModel>(*aligned, set, std::move(skeleton), record->frame_rate, weight, options);
}

}  // namespace mocapdb::workflow
