#pragma once
// Motion synthesis at control parameters c: the interface shared by the compressed model
// (motion_model.hpp: kriging of the Tucker sample-mode coefficients, the multilinear paper) and the
// naive baseline (naive_motion_model.hpp: kriging of the uncompressed aligned tensor), so benchmarks,
// evaluations and the CLI swap one for the other.
//
// Details: docs/headers/synthesis.md (mocapdb/synthesis/synthesis_model.hpp).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/core/types.hpp"
#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/aligned_timing.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/kriging_predictor.hpp"
#include "mocapdb/kriging/local_kriging.hpp"
#include "mocapdb/kriging/motion_kriging.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "mocapdb/kriging/variogram_fit.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/skeleton.hpp"
#include "mocapdb/synthesis/kernel_fit.hpp"
#include "mocapdb/synthesis/predictor_choice.hpp"
#include "mocapdb/tensor/tucker.hpp"

namespace mocapdb::synthesis {

/// How the kernels are built (defaults: the papers).
struct SynthesisOptions {
    /// Model exponent p of the coefficient kernel (0 = spherical, 0 < p <= 2 stable); empty = chosen by
    /// closed-form leave-one-out over kriging::paper_exponent_grid().
    std::optional<double> exponent;
    /// Same for a Separate timing kernel; empty = chosen by leave-one-out on the increments.
    std::optional<double> timing_exponent;
    /// Timing kernel (see the header comment): Shared = the coefficient kernel's weights blend the
    /// increments too; Separate = a second per-set kriging of the increments (the paper's Section 3.5).
    enum class TimingKernel { Shared, Separate } timing_kernel = TimingKernel::Shared;
    /// The experimental variogram of the coefficient kernel, estimated on the trend residuals.
    /// Matheron by default: the Cressie-Hawkins constant 0.457 assumes scalar Gaussian differences, and for
    /// a distance between many-dimensional vectors it overstates gamma by up to 1 / 0.457 = 2.2.
    kriging::VariogramOptions variogram = matheron_variogram();
    /// Fit options; fit_coefficient_kernel adds the bounds below (range, total sill, nugget of p = 2).
    kriging::VariogramFitOptions fit;
    /// Kriging options: trend Linear + OLS (the paper); the nugget filtered (measurement noise, so that
    /// synthesis is continuous in c), rho from the prediction variance.
    kriging::KrigingOptions kriging = filtered_kriging();
    /// Candidate exponents of the leave-one-out choice (paper convention, 0 = spherical). Default: 0 and
    /// 1.0, 1.2, ..., 2.0: a stable model with p < 1 rises as h^p with an infinite slope at 0, so a tiny
    /// step away from a sample moves the weights by (h / range)^p (0.16 at h = 1e-4 range for p = 0.2).
    std::vector<double> exponent_grid = {0.0, 1.0, 1.2, 1.4, 1.6, 1.8, 2.0};
    /// Upper bound of the range, as a multiple of the largest lag of the experimental variogram.
    double max_range_factor = 1.0;
    /// Upper bound of nugget + sill, as a multiple of the residual variance (sum over values of the
    /// residual variances of the linear trend, divided by N - K).
    double max_sill_factor = 2.0;
    /// Smallest nugget of a Gaussian (p = 2) model, as a fraction of the residual variance.
    double gaussian_nugget_fraction = 0.01;
    /// How range and nugget share of the coefficient kernel are chosen: LeastSquares = the
    /// weighted least-squares fit to the experimental variogram only; LeaveOneOut (default) = that fit and a
    /// bounded grid of ranges (range_fractions of the range bound) and nugget shares, the candidate with the
    /// smallest closed-form leave-one-out error of the sample values wins (kernel_fit.hpp).
    enum class ShapeSelection { LeastSquares, LeaveOneOut } shape_selection = ShapeSelection::LeaveOneOut;
    /// Candidate ranges of the LeaveOneOut shape search, as fractions (0, 1] of the range bound.
    std::vector<double> range_fractions = {0.1, 0.2, 0.35, 0.5, 0.75, 1.0};
    /// Candidate nugget shares nugget / (nugget + sill) in [0, 1) of the LeaveOneOut shape search.
    std::vector<double> nugget_shares = {0.0, 0.15, 0.4};

    static kriging::VariogramOptions matheron_variogram() {
        kriging::VariogramOptions v;
        v.estimator = kriging::VariogramEstimator::Matheron;
        return v;
    }
    static kriging::KrigingOptions filtered_kriging() {
        kriging::KrigingOptions k;
        k.filter_nugget = true;
        return k;
    }
    /// Normalization of the control parameters; empty = per-axis mean / standard deviation of the samples.
    std::optional<kriging::ControlScaling> scaling;
    /// Compressed model only: extra level-of-detail ranks (1 <= r_n <= the model's ranks); level 0 is
    /// always the full model, level k the k-th entry here.
    std::vector<tensor::Ranks> levels;
    /// Lower clamp of a kriged inverse-warp increment, as a fraction (0, 1] of the mean sample increment.
    double min_increment_fraction = 0.05;
    /// Upper clamp of a kriged inverse-warp increment, as a multiple (>= 1) of the largest sample increment.
    double max_increment_factor = 4.0;
    /// Sets of more samples choose their coefficient kernel's variogram on this many of them, evenly spread
    /// in sample order (a subset of data: the leave-one-out choice costs O(n^3) and O(n^2) memory per
    /// candidate; docs/synthesis-scale.md). The kriging system keeps every sample. >= 2.
    std::size_t max_fit_samples = 1000;
    /// fit_kernel factorizes the kriging system for storage (KernelFit::system: N^2 doubles, 74 MB at
    /// N = 3 043) for sets of up to this many samples; larger sets factorize it at every load (O(N^3):
    /// docs/synthesis-scale.md gives the costs).
    std::size_t max_stored_system_samples = 6000;
    /// Sets of more samples are synthesized by local kriging (kriging/local_kriging.hpp: each query by
    /// its local_neighbours nearest samples, the same variogram and trend), with no N x N matrix anywhere:
    /// O(N k) memory at most, O(k^3) per query; fit_kernel stores no system for them. Up to this many,
    /// the exact kriging of all samples. The error of the approximation: docs/synthesis-scale.md.
    std::size_t max_exact_samples = 6000;
    /// k of the local kriging (>= 1): 300 keeps one query at a few milliseconds.
    std::size_t local_neighbours = 300;
    /// Called while the coefficient kernel is fitted (item "kernel": one step per candidate variogram
    /// scored by leave-one-out) and while its kriging system is factorized (item "kernel system": columns
    /// of the inverse; by fit_kernel for storage, and at construction when no stored system is used); not
    /// part of the kernel's key; may be empty. The library never prints.
    ProgressCallback fit_progress;
    /// Compressed model only: a precomputed coefficient kernel (kernel_fit.hpp; workflow::load_motion_model reads
    /// the stored one). Used when its key equals kernel_key of the model's inputs and these options,
    /// ignored otherwise (the kernel is then fitted as without it). The naive model ignores it.
    std::optional<KernelFit> kernel_fit;
    /// The interpolator of the sample weights (predictor_choice.hpp); empty = kriging (a stored model's
    /// default is the choice stored with its kernel: workflow::load_motion_model). rho always comes from
    /// the kriging kernel.
    std::optional<Predictor> predictor;
    /// predictor = Average: the candidates whose weights are averaged (two or three distinct of kriging,
    /// rbf, trend; use_predictor_choice sets them); ignored otherwise.
    std::vector<Predictor> averaged;
};

/// options.predictor (and options.averaged) as `choice` chose.
void use_predictor_choice(const PredictorChoice& choice, SynthesisOptions& options);

/// What was built (for reports and the CLI).
struct SynthesisReport {
    kriging::VariogramModel model;  ///< coefficient kernel's variogram
    kriging::KrigingStatus status;  ///< its factorization
    kriging::FitStatus fit_status =
        kriging::FitStatus::Ok;  ///< of the variogram fit (precomputed: KernelFit::assessed_status, else recomputed)
    std::optional<double> loo_mean_z2;  ///< KernelFit::loo_mean_z2 (none when the kernel was precomputed)
    Eigen::VectorXd exponent_loo_mse;  ///< LOO MSE per grid exponent (empty when p was given or the kernel precomputed)
    double timing_exponent = 0.0;      ///< p of the timing kernel (Shared: the coefficient kernel's)
    double precompute_seconds = 0.0;   ///< construction time of the two kriging kernels
    bool kernel_precomputed = false;   ///< the coefficient kernel's variogram came from options.kernel_fit
    bool system_precomputed = false;   ///< and its factorized system (KernelFit::system) too
    Predictor predictor = Predictor::Kriging;  ///< what blends the samples (SynthesisOptions::predictor)
    /// 0: the exact kriging of all samples; else k of the local kriging (N > max_exact_samples).
    Eigen::Index local_neighbours = 0;
    /// The cross-validated choice stored with the kernel (empty for a kernel fitted here or stored without it).
    std::optional<PredictorChoice> predictor_choice;
};

/// The synthesized timing of one motion.
struct Timing {
    VecX increments;  ///< T - 1: kriged inverse-warp increments after clamping (source frames per aligned frame)
    VecX warp;        ///< T: A_c(t), the synthesized frame shown at aligned frame t; warp(0) = 0
    Eigen::Index clamped = 0;  ///< increments that hit a clamp
    /// Frames of the synthesized motion at the set's frame rate: floor(warp(T - 1)) + 1.
    Eigen::Index frame_count() const;
    /// The fractional aligned frame t in [0, T - 1] at which the synthesized clip shows frame f
    /// (the inverse of warp, piecewise linear; clamped at both ends).
    double aligned_frame(double f) const;
};

/// Scratch memory of single queries; one per thread, reused (sized on first use).
struct Workspace {
    kriging::QueryWorkspace kriging;
    VecX c_normalized;
    VecX weights;
    VecX coefficients;
    Eigen::RowVectorXd u_time;
    Eigen::RowVectorXd u_sample;
    tensor::PoseEvaluator::Workspace pose;
};

/// Scratch memory of batched queries (allocation on size changes only, apart from the kriging batch).
struct BatchWorkspace {
    MatX c_normalized;  ///< Q by P
    MatX weights;       ///< N by Q
    MatX coefficients;  ///< S by Q
    MatX frame_matrix;  ///< model-specific per-frame operator
    MatX kriging;       ///< (N + K) by block: the kriging right-hand sides of a block of characters
    MatX core_time;     ///< model-specific: the core contracted with the frame's time row
    Eigen::RowVectorXd u_time;
};

/// The interface of every synthesis model (see the header comment).
class SynthesisModel {
public:
    virtual ~SynthesisModel() = default;
    SynthesisModel(const SynthesisModel&) = delete;
    SynthesisModel& operator=(const SynthesisModel&) = delete;

    /// "tucker" or "naive".
    virtual const char* kind() const = 0;

    Eigen::Index dofs() const { return dofs_; }
    Eigen::Index frames() const { return frames_; }             ///< T, aligned frames
    Eigen::Index samples() const { return coords_.rows(); }     ///< N
    Eigen::Index parameters() const { return coords_.cols(); }  ///< P
    const std::vector<std::string>& parameter_names() const { return names_; }
    const std::vector<std::string>& parameter_units() const { return units_; }
    const MatX& sample_parameters() const { return coords_; }  ///< N by P, the set's units
    const kriging::ControlScaling& scaling() const { return scaling_; }
    const std::shared_ptr<const Skeleton>& skeleton() const { return skeleton_; }
    double frame_rate() const { return frame_rate_; }
    const SynthesisReport& report() const { return report_; }
    /// The coefficient kernel's exact kriging; InvalidArgument when the model uses the local kriging
    /// (local_kernel()), which has no global system.
    const kriging::Kriging& kernel() const;
    /// The local kriging of a set of more than max_exact_samples samples; null for the exact kriging.
    const kriging::LocalKriging* local_kernel() const { return local_.get(); }
    /// The coefficient kernel's kriging options (either kriging).
    const kriging::KrigingOptions& kriging_options() const { return kriging_options_; }
    /// The coefficient kernel's variogram and LOO MSE, with the key of the model's inputs (0 for the
    /// naive model): what `compress` stores (kernel_fit.hpp).
    const KernelFit& kernel_fit() const { return kernel_fit_; }

    /// Number of levels of detail (>= 1; level 0 = full). The naive model has one.
    virtual Eigen::Index levels() const = 0;
    /// Ranks of a level (the naive model: (D, T, N)).
    virtual tensor::Ranks level_ranks(Eigen::Index level) const = 0;
    /// S, the length of a motion's coefficient vector (compressed: R3; naive: N).
    virtual Eigen::Index coefficient_size() const = 0;
    /// Approximate bytes held by the model (matrices and tensors, not the skeleton).
    virtual std::size_t memory_bytes() const;

    /// Kriging weights w(c) of the samples: c P (set's units), out N.
    void weights(const Eigen::Ref<const VecX>& c, Eigen::Ref<VecX> out, Workspace& ws) const;
    /// The coefficient vector of the motion at c: out S.
    void coefficients(const Eigen::Ref<const VecX>& c, Eigen::Ref<VecX> out, Workspace& ws) const;
    /// The pose vector (D) of the motion with coefficients `coefficients` (S) at fractional aligned
    /// frame t in [0, T - 1] (linear between the neighbouring frames), at a level of detail.
    virtual void pose_from_coefficients(const Eigen::Ref<const VecX>& coefficients, double t, Eigen::Ref<VecX> out,
                                        Workspace& ws, Eigen::Index level = 0) const = 0;
    /// pose(c, t) = pose_from_coefficients(coefficients(c), t).
    void pose(const Eigen::Ref<const VecX>& c, double t, Eigen::Ref<VecX> out, Workspace& ws,
              Eigen::Index level = 0) const;
    /// Allocating convenience: the pose vector (D).
    VecX pose(const Eigen::Ref<const VecX>& c, double t, Eigen::Index level = 0) const;

    /// Many characters at one aligned frame: C Q by P (one row per character), out D by Q.
    void poses(const Eigen::Ref<const MatX>& C, double t, Eigen::Ref<MatX> out, BatchWorkspace& ws,
               Eigen::Index level = 0) const;
    /// Many characters with precomputed coefficients (S by Q) at one aligned frame: out D by Q.
    virtual void poses_from_coefficients(const Eigen::Ref<const MatX>& coefficients, double t, Eigen::Ref<MatX> out,
                                         BatchWorkspace& ws, Eigen::Index level = 0) const = 0;

    /// The kriged timing at c.
    Timing timing(const Eigen::Ref<const VecX>& c) const;
    /// Pose vectors (D by F) of the synthesized motion at c: frame f at aligned frame timing.aligned_frame(f).
    MatX motion_poses(const Eigen::Ref<const VecX>& c, Eigen::Index level = 0) const;
    /// The synthesized motion at c as a clip (the set's skeleton and frame rate; the root trajectory is
    /// the synthesized canonical root position and heading, starting at the origin facing +Z), ready for
    /// write_bvh.
    Clip motion(const Eigen::Ref<const VecX>& c, Eigen::Index level = 0) const;

    /// rho(c) in [0, 1] of the coefficient kernel.
    double reliability(const Eigen::Ref<const VecX>& c) const;
    /// rho at Q queries (Q by P); returns Q.
    VecX reliability_batch(const Eigen::Ref<const MatX>& C) const;
    /// The coefficient kernel's prediction variance at c over its total sill, not clamped: rho =
    /// clamp(1 - ratio, 0, 1), and beyond rho = 0 the ratio keeps growing away from the samples
    /// (the trend's extrapolation), which the calibrated warning uses (workflow/edge_calibration.hpp).
    double variance_ratio(const Eigen::Ref<const VecX>& c) const;

protected:
    /// Common construction: parameters, scaling, the timing kernel and the coefficient kernel whose
    /// variogram and leave-one-out use the Euclidean distances between the rows of `sample_values()`
    /// (N by anything; called only when the variogram is fitted here). key: kernel_key of the inputs
    /// (0: never use options.kernel_fit); when options.kernel_fit has this key its variogram is used.
    /// timing: the aligned form's warps and D x T x N (validate(AlignedTiming) is checked here; a derived
    /// model that uses the tensor checks the whole aligned set first, checked_timing).
    SynthesisModel(const AlignedTiming& timing, const MotionSet& set, std::shared_ptr<const Skeleton> skeleton,
                   double frame_rate, const std::function<MatX()>& sample_values, std::uint64_t key,
                   const SynthesisOptions& options, const char* where);

    /// validate(aligned) (the tensor's values included), then timing_of(aligned).
    static AlignedTiming checked_timing(const AlignedSet& aligned);

    /// Coefficients from kriging weights (N) into out (S).
    virtual void coefficients_from_weights(const Eigen::Ref<const VecX>& w, Eigen::Ref<VecX> out) const = 0;
    virtual void coefficients_from_weights_batch(const Eigen::Ref<const MatX>& w, MatX& out) const = 0;
    /// Throws InvalidArgument for t outside [0, T - 1] or a bad level; returns the frame pair and fraction.
    void frame_pair(double t, Eigen::Index level, Eigen::Index& t0, Eigen::Index& t1, double& a,
                    const char* where) const;
    void normalize(const Eigen::Ref<const VecX>& c, VecX& out, const char* where) const;
    /// What blends the samples: the predictor asked for, else the local or the exact kriging.
    const kriging::Interpolator& weight_interpolator() const;
    /// rho at normalized queries (Q by embedded P) from the coefficient kernel.
    VecX kernel_reliability(const Eigen::Ref<const MatX>& xc) const;

    Eigen::Index dofs_ = 0;
    Eigen::Index frames_ = 0;
    std::vector<std::string> names_;
    std::vector<std::string> units_;
    MatX coords_;
    kriging::ControlScaling scaling_;
    kriging::Kriging kriging_;  ///< empty when local_ is set
    /// The local kriging (N > options.max_exact_samples), null otherwise.
    std::unique_ptr<kriging::LocalKriging> local_;
    kriging::KrigingOptions kriging_options_;
    /// The weights' interpolator when report_.predictor is not kriging (null for kriging).
    std::unique_ptr<kriging::Interpolator> predictor_;
    KernelFit kernel_fit_;
    /// When not empty (set by the derived model, for the kriging predictor only): the coefficient vectors
    /// folded into the kriging operator, used by coefficients() and poses() instead of weights + coefficients_from_weights.
    kriging::KrigingPredictor folded_;
    kriging::MotionKriging timing_;
    SynthesisOptions::TimingKernel timing_kernel_ = SynthesisOptions::TimingKernel::Shared;
    MatX increments_;  ///< N by T - 1 inverse-warp increments of the samples
    double min_increment_ = 0.0;
    double max_increment_ = 0.0;
    std::shared_ptr<const Skeleton> skeleton_;
    double frame_rate_ = 0.0;
    SynthesisReport report_;
};

}  // namespace mocapdb::synthesis
