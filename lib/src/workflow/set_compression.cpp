#include "mocapdb/core/stopwatch.hpp"
#include "mocapdb/workflow/set_compression.hpp"

#include <algorithm>
#include <chrono>
#include <sstream>

#include "mocapdb/compression/byte_accounting.hpp"
#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/rank_search.hpp"
#include "mocapdb/compression/rate_distortion.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/synthesis/kernel_fit.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"
#include "mocapdb/workflow/edge_calibration.hpp"

namespace mocapdb::workflow {
namespace {

using Clock = std::chrono::steady_clock;

std::string ranks_text(const tensor::Ranks& r) {
    return std::to_string(r[0]) + "x" + std::to_string(r[1]) + "x" + std::to_string(r[2]);
}

// The ranks by the request's target, with the model at them. The bases live only here: released
// before the model is decomposed and stored (#16: about 0.5 GB at 11 070 windows). Sets o.criterion
// and o.search_s.
compression::RankSearchResult choose_ranks(compression::PreparedSet prepared, const compression::JointErrorMeter& meter,
                                           const CompressRequest& a, CompressOutcome& o) {
    compression::RankSearchResult chosen;
    const auto search_start = Clock::now();
    if (a.ranks) {
        const tensor::Ranks& r = *a.ranks;
        for (std::size_t n = 0; n < 3; ++n)
            if (r[n] < 1 || r[n] > o.dims[n])
                throw Refused<InvalidArgument>(Remedy::Ranks, "ranks: rank " + std::to_string(n + 1) +
                                                                  " must be in [1, " + std::to_string(o.dims[n]) +
                                                                  "] for a tensor of " + ranks_text(o.dims) +
                                                                  " (dofs x frames x samples)");
        chosen.model = compression::hosvd_model(prepared, r);
        chosen.target_met = true;
        o.criterion = "ranks " + ranks_text(r);
    } else if (a.rmse >= 0.0) {
        chosen = compression::search_ranks_for_rmse(prepared, meter, a.rmse, a.progress);
        o.criterion = "rmse <= " + std::to_string(a.rmse);
    } else if (a.ratio > 0.0) {
        chosen = compression::ranks_for_ratio(prepared, meter, a.ratio);
        o.criterion = "ratio >= " + std::to_string(a.ratio);
    } else {
        const double target = a.max_error_cm > 0.0 ? a.max_error_cm : 1.0;
        chosen = compression::search_ranks_for_max_error(std::move(prepared), meter, target, a.progress);
        std::ostringstream s;
        s << "max joint error <= " << target << " cm";
        o.criterion = s.str();
    }
    o.search_s = seconds_since(search_start);
    return chosen;
}

// rho's warning threshold calibrated on the set's own syntheses (edge_calibration.hpp), where the
// parameters are measured back and the kernel's system is stored (the model then builds in O(N^2);
// above max_stored_system_samples the fixed threshold stays).
void calibrate_warning(const compression::SetModel& model, const AlignedSetData& c, synthesis::KernelFit& kernel,
                       const ProgressCallback& progress) {
    const auto tolerance = parameter_tolerance(c.set, EdgeCalibrationOptions{}.tolerance_share);
    if (!kernel.system || std::none_of(tolerance.begin(), tolerance.end(), [](const auto& t) { return t.has_value(); }))
        return;
    synthesis::SynthesisOptions options;
    options.kernel_fit = kernel;
    if (kernel.predictor) synthesis::use_predictor_choice(*kernel.predictor, options);
    const synthesis::MotionModel synth(model, timing_of(c.aligned), c.set, c.skeleton, c.frame_rate, options);
    kernel.edge_warning = calibrate_edge_warning(edge_probes(synth, c.set, {}, progress), c.set);
}

}  // namespace

CompressOutcome compress_set(const std::filesystem::path& db, const CompressRequest& a) {
    const auto start = Clock::now();
    AlignedSetData c = load_aligned_set(Database(db), a.set);
    const VecX weight = compression::position_error_weights(*c.skeleton);
    CompressOutcome o;
    o.load_s = seconds_since(start);
    o.dims = tensor::dims_of(c.aligned.tensor);
    o.raw_bytes = compression::aligned_float32_bytes(c.aligned.tensor);

    // The set is held once (#16: 0.48 GB at 11 070 windows): its tensor becomes the weighted, centred
    // X in place (x below, from here on), and the meter reads the poses back from it.
    const auto bases_start = Clock::now();
    compression::PreparedSet prepared = compression::prepare_set_in_place(c.aligned.tensor, weight);
    o.bases_s = seconds_since(bases_start);
    const Tensor3& x = c.aligned.tensor;
    const VecX mean = prepared.mean;
    const auto meter_start = Clock::now();
    const compression::JointErrorMeter meter(c.skeleton, x, mean, weight);
    o.load_s += seconds_since(meter_start);  // the reference's joint positions, counted with the load as before
    compression::RankSearchResult chosen = choose_ranks(std::move(prepared), meter, a, o);
    o.target_met = chosen.target_met;

    // The chosen ranks, decomposed with the requested method. HOSVD is the search's own model (the
    // model fit_set_model would compute from the same bases) with its measured errors: no second
    // pass over the set.
    const auto fit_start = Clock::now();
    tensor::HooiOptions hooi;
    hooi.max_iterations = a.max_iterations;
    const bool reuse = a.method == tensor::TuckerMethod::Hosvd;
    o.model = reuse ? std::move(chosen.model)
                    : compression::fit_weighted_set_model(x, mean, weight, chosen.model.tucker.ranks, a.method, hooi);
    o.fit_s = seconds_since(fit_start);
    o.stats = reuse && chosen.stats.positions > 0 ? chosen.stats : meter.measure(o.model.reconstruct());
    o.us_per_pose = compression::time_pose_evaluation(o.model.tucker);

    // The synthesis kernel's variogram, fitted once here so that synthesis need not (#16; kernel_fit.hpp),
    // for any number of samples: above SynthesisOptions::max_fit_samples it is chosen on a subset, so
    // its cost is bounded. A set without control parameters compresses, but has nothing to
    // synthesize over: no kernel.
    const auto kernel_start = Clock::now();
    std::optional<synthesis::KernelFit> kernel;
    // (fit_kernel reads only the aligned tensor's shape, which x keeps.)
    if (c.set.parameters.cols() > 0) {
        synthesis::SynthesisOptions options;
        options.fit_progress = a.kernel_progress;
        kernel = synthesis::fit_kernel(o.model, c.aligned, c.set, options);
        o.kernel_fit_samples = kernel->fit_samples;
    }
    o.kernel_stored = kernel.has_value();
    if (!kernel) o.kernel_not_stored_reason = "the set has no control parameters: nothing to synthesize at";
    if (kernel) {
        o.kernel_variogram = kernel->variogram.to_string();
        o.kernel_status = kernel->status;
        o.kernel_warning = synthesis::fit_status_warning(*kernel);
        o.kernel_predictor = kernel->predictor;
        calibrate_warning(o.model, c, *kernel, a.kernel_progress);
        o.kernel_edge_warning = kernel->edge_warning;
    }
    o.kernel_s = seconds_since(kernel_start);  // the warning's calibration included

    const auto store_start = Clock::now();
    const ModelFigures figures{o.stats.dof_rmse, o.stats.rmse_cm, o.stats.mean_cm, o.stats.max_cm, o.stats.p99_cm};
    DatabaseWriter writer(db, DatabaseWriter::Mode::OpenOrCreate);
    writer.put_model(a.set, o.model, figures);
    if (kernel) writer.put_kernel_fit(a.set, *kernel);
    writer.commit();
    for (const SetRecord& r : Database(db).sets())
        if (r.name == a.set) o.stored_bytes = r.model_stored_bytes;
    o.store_s = seconds_since(store_start);

    o.bytes = compression::tucker_float32_bytes(o.model) +
              compression::side_info_bytes(o.dims[1], o.dims[2], c.set.parameters.cols());
    o.total_s = seconds_since(start);
    return o;
}

}  // namespace mocapdb::workflow
