#pragma once
// `mocapdb compress` as a library step: choose the Tucker ranks of a set's aligned tensor
// (explicit, or the smallest meeting a max joint error, a weighted RMSE or a compression ratio;
// compression/rank_search.hpp), decompose with the requested method, measure the joint-position
// errors after forward kinematics, fit the synthesis kernel's variogram (synthesis/kernel_fit.hpp; on a
// subset above SynthesisOptions::max_fit_samples samples), calibrate rho's warning threshold on the set
// (edge_calibration.hpp) and store model and kernel, committed (replacing the set's previous model). Nothing is printed: every figure is in the outcome.
//
// Errors: InvalidArgument (no such set, the set not aligned, a rank outside [1, dimension]),
// StoreError / IoError from the database; nothing is stored when it throws. Threads: the database's
// writer lock serializes writers.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/core/progress.hpp"
#include "mocapdb/kriging/variogram_fit.hpp"
#include "mocapdb/synthesis/predictor_choice.hpp"
#include "mocapdb/tensor/tucker.hpp"

namespace mocapdb::workflow {

/// The target, by precedence: ranks, else rmse >= 0, else ratio > 0, else max_error_cm (1 cm when 0).
struct CompressRequest {
    std::string set;
    std::optional<tensor::Ranks> ranks;  ///< explicit ranks (dof, time, sample)
    double max_error_cm = 0.0;           ///< max joint-position error target, cm; 0 = 1 cm
    double rmse = -1.0;                  ///< RMSE target of the weighted, centred tensor; < 0 = none
    double ratio = 0.0;                  ///< compression ratio target of the Tucker parameters; 0 = none
    tensor::TuckerMethod method = tensor::TuckerMethod::Hosvd;
    int max_iterations = 50;           ///< HOOI sweeps at most
    ProgressCallback progress;         ///< the rank search's (max error and rmse targets); may be empty
    ProgressCallback kernel_progress;  ///< the synthesis kernel's fit (SynthesisOptions::fit_progress); may be empty
};

struct CompressOutcome {
    std::string criterion;        ///< the target as text: "max joint error <= 1 cm", "ranks 22x6x24", ...
    bool target_met = false;      ///< false: the closest ranks the search found
    tensor::Dims3 dims{0, 0, 0};  ///< of the aligned tensor
    compression::SetModel model;
    compression::JointErrorStats stats;  ///< measured on the model against the aligned tensor
    double us_per_pose = 0.0;            ///< one pose evaluated from the model
    std::uint64_t raw_bytes = 0;         ///< aligned tensor as float32
    std::uint64_t bytes = 0;             ///< float32 model + side information
    std::uint64_t stored_bytes = 0;      ///< the model in the file
    double load_s = 0.0;                 ///< reading the aligned set
    double bases_s = 0.0;                ///< centring, weighting and the HOSVD bases (every mode's spectrum)
    double search_s = 0.0;               ///< the rank search (or the explicit ranks' model)
    double fit_s = 0.0;                  ///< decomposing at the chosen ranks with the requested method
    double store_s = 0.0;                ///< writing and committing model and kernel
    double total_s = 0.0;
    double kernel_s = 0.0;  ///< fitting the synthesis kernel stored with the model, its warning calibration included
    bool kernel_stored = false;            ///< false without parameters
    std::size_t kernel_fit_samples = 0;    ///< samples its variogram was chosen on (KernelFit::fit_samples)
    std::string kernel_not_stored_reason;  ///< why not, when not ("" when stored)
    std::string kernel_variogram;          ///< the stored kernel's variogram (empty when not stored)
    kriging::FitStatus kernel_status = kriging::FitStatus::Ok;  ///< its fit status
    std::string kernel_warning;  ///< synthesis::fit_status_warning, "" when the fit is clean
    /// The predictor cross-validation chose, stored with the kernel (synthesis/predictor_choice.hpp);
    /// empty without a kernel or when no sample could be left out.
    std::optional<synthesis::PredictorChoice> kernel_predictor;
    /// rho's warning threshold calibrated on the set and stored with the kernel (KernelFit::edge_warning);
    /// empty without a kernel, without parameters measured back, or above max_stored_system_samples.
    std::optional<synthesis::EdgeWarning> kernel_edge_warning;

    double ratio() const { return static_cast<double>(raw_bytes) / static_cast<double>(bytes); }
};

/// Rank search (or explicit ranks), decomposition, measurement, and the model stored (committed).
CompressOutcome compress_set(const std::filesystem::path& db, const CompressRequest& request);

}  // namespace mocapdb::workflow
