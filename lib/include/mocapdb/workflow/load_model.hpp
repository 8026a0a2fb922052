#pragma once
// Synthesis models built from what a database stores (the first step of the workflow module:
// it depends on the store and on synthesis, which do not depend on each other's loading).
// Thread safety: the Database must not be written meanwhile; the returned models are immutable.
#include <memory>
#include <string>

#include "mocapdb/store/database.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/synthesis/naive_motion_model.hpp"

namespace mocapdb::workflow {

/// The set's stored model (`mocapdb compress`), aligned timing and shape (load_aligned_timing: the
/// aligned tensor's values are not read, the model does not use them), parameters, skeleton and frame
/// rate from the database, and (unless options.kernel_fit is set) the model's stored kernel fit
/// (Database::load_kernel_fit; used when its key matches, kernel_fit.hpp) with, unless options.predictor
/// is set, the predictor stored with it (predictor_choice.hpp). InvalidArgument naming the
/// command to run when the set is not aligned or has no model; StoreError for a malformed stored kernel.
std::unique_ptr<synthesis::MotionModel> load_motion_model(const Database& db, const std::string& set,
                                                          const synthesis::SynthesisOptions& options = {});

/// The set's aligned form, parameters, skeleton and frame rate from the database, with
/// compression::position_error_weights of the skeleton. InvalidArgument when the set is not aligned.
std::unique_ptr<synthesis::NaiveMotionModel> load_naive_motion_model(const Database& db, const std::string& set,
                                                                     const synthesis::SynthesisOptions& options = {});

}  // namespace mocapdb::workflow
