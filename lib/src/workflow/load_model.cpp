#include "mocapdb/workflow/load_model.hpp"

#include <utility>

#include "mocapdb/store/database.hpp"

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"

namespace mocapdb::workflow {

namespace {

// Synthesis interpolates over the set's control parameters: a set without any has nothing to ask for.
void require_parameters(const Database& db, const std::string& name) {
    if (db.load_set(name).parameters.cols() == 0)
        throw Refused<InvalidArgument>(Remedy::GiveParameters,
                                       "set '" + name + "' in " + db.path().string() +
                                           " has no control parameters, so there is nothing to synthesize at");
}

}  // namespace

std::unique_ptr<synthesis::MotionModel> load_motion_model(const Database& db, const std::string& name,
                                                          const synthesis::SynthesisOptions& options) {
    require_parameters(db, name);
    AlignedTimingData d = load_aligned_timing(db, name);  // the model has its own poses: not the tensor's values
    auto stored = db.load_model(name);
    if (!stored)
        throw Refused<InvalidArgument>(Remedy::CompressFirst,
                                       "set '" + name + "' in " + db.path().string() + " has no compressed model");
    synthesis::SynthesisOptions with_fit = options;
    if (!with_fit.kernel_fit) with_fit.kernel_fit = db.load_kernel_fit(name);  // nullopt for models stored without one
    // The predictor compress chose for these inputs, unless another is asked for.
    if (!with_fit.predictor && with_fit.kernel_fit && with_fit.kernel_fit->predictor &&
        with_fit.kernel_fit->key == synthesis::kernel_key(stored->model, d.set, with_fit))
        synthesis::use_predictor_choice(*with_fit.kernel_fit->predictor, with_fit);
    return std::make_unique<synthesis::MotionModel>(std::move(stored->model), d.timing, d.set, std::move(d.skeleton),
                                                    d.frame_rate, with_fit);
}

std::unique_ptr<synthesis::NaiveMotionModel> load_naive_motion_model(const Database& db, const std::string& name,
                                                                     const synthesis::SynthesisOptions& options) {
    require_parameters(db, name);
    AlignedSetData d = load_aligned_set(db, name);
    const VecX weight = compression::position_error_weights(*d.skeleton);
    return std::make_unique<synthesis::NaiveMotionModel>(d.aligned, d.set, std::move(d.skeleton), d.frame_rate, weight,
                                                         options);
}

}  // namespace mocapdb::workflow
