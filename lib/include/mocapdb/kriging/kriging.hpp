#pragma once
// Ordinary and universal kriging with a fixed variogram model (paper Sections 3, 4.3, Appendix B).
//
// The object is immutable after build() and safe to query from several threads (one QueryWorkspace
// per thread).
//
// Details: docs/headers/kriging.md (mocapdb/kriging/kriging.hpp).
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/kriging/interpolator.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/kriging/variogram_model.hpp"

namespace mocapdb::kriging {

namespace detail {
struct QueryOperator;
}  // namespace detail

enum class TrendFit {
    OLS,  ///< paper: least-squares hyperplane, ordinary kriging of its residuals.
    GLS,  ///< standard universal kriging (generalized least squares trend).
};

enum class DuplicatePolicy {
    Merge,  ///< merge coincident control points into one sample (mean value); weights split evenly.
    Keep,   ///< keep them (the system is then regularized by the nugget or the jitter).
};

enum class FactorizationStatus {
    Ok,           ///< Cholesky of the covariance matrix succeeded as is.
    Jittered,     ///< a small multiple of the identity was added (see KrigingStatus::jitter).
    Regularized,  ///< eigenvalues were clamped to make the covariance matrix positive definite.
};

const char* to_string(TrendFit fit);
const char* to_string(FactorizationStatus status);

/// Which variance the reliability rho = 1 - V / total sill is computed from (see the header comment).
enum class ReliabilityVariance {
    Prediction,  ///< the predictor's error variance (`variance`, universal kriging with the trend terms).
    Paper,       ///< the paper's sigma^2 = sum b_i gamma_i (Appendix B; clipped at 0 when it goes negative).
};

const char* to_string(ReliabilityVariance v);

struct KrigingOptions {
    TrendKind trend = TrendKind::Linear;
    TrendFit trend_fit = TrendFit::OLS;
    DuplicatePolicy duplicates = DuplicatePolicy::Merge;
    double duplicate_tolerance = 0.0;  ///< >= 0: points at distance <= this are duplicates.
    /// In [0, 1): smallest acceptable reciprocal condition estimate of the covariance matrix. Weights are
    /// accurate to about 1e-16 / rcond, so below this the jitter is escalated instead.
    double min_rcond = 1e-10;
    double max_jitter = 1e-3;             ///< > 0: largest jitter tried, relative to the total sill.
    double trend_rank_tolerance = 1e-10;  ///< see TrendBasis::build.
    /// Filtered kriging: the nugget is noise (see the header comment). false = exact interpolation.
    bool filter_nugget = false;
    ReliabilityVariance reliability = ReliabilityVariance::Prediction;
};

struct KrigingStatus {
    FactorizationStatus factorization = FactorizationStatus::Ok;
    double jitter = 0.0;                 ///< absolute value added to the covariance diagonal.
    double rcond = 0.0;                  ///< reciprocal condition estimate of the factorized covariance matrix.
    Eigen::Index unique_points = 0;      ///< number of control points after merging duplicates.
    Eigen::Index duplicates_merged = 0;  ///< N - unique_points (0 with DuplicatePolicy::Keep).
    Eigen::Index duplicate_pairs = 0;    ///< pairs of samples within duplicate_tolerance (either policy).
    Eigen::Index trend_rank = 0;         ///< rank of the linear trend part kept (0 for no trend).
    bool trend_rank_deficient = false;   ///< control points do not span all P dimensions.
    /// True when the result is exact (no jitter, no regularization).
    bool exact() const { return factorization == FactorizationStatus::Ok; }
};

/// Everything about one query point.
struct KrigingEstimate {
    Eigen::VectorXd weights;      ///< N: w(c), applied to raw samples.
    Eigen::VectorXd kernel;       ///< N: b(c) of the paper's Equation 3 (== weights for OK / GLS).
    double variance = 0.0;        ///< kriging (prediction-error) variance, >= 0.
    double paper_variance = 0.0;  ///< sigma^2(c) = sum_i b_i gamma(|c - c_i|), >= 0.
    double reliability = 0.0;     ///< rho(c) in [0, 1].
};

/// Per-query scalars of a batch plus the weights.
struct KrigingBatch {
    Eigen::MatrixXd weights;         ///< N by Q.
    Eigen::VectorXd variance;        ///< Q.
    Eigen::VectorXd paper_variance;  ///< Q.
    Eigen::VectorXd reliability;     ///< Q.
};

/// Leave-one-out cross validation, in closed form from the one factorization (Dubrule 1983): for
/// sample i the prediction from all others, without refitting. With GLS / ordinary kriging this is
/// exactly what refitting N times would give (the trend is re-estimated without the sample, as gstat's
/// krige.cv does). With OLS it follows the paper's Appendix A: the residuals of the full-data trend are
/// kept and the left-out residual is predicted from the others.
struct LooResult {
    Eigen::MatrixXd prediction;  ///< N by D.
    Eigen::MatrixXd residual;    ///< N by D: observed - prediction.
    Eigen::VectorXd variance;    ///< N: kriging variance of each left-out prediction (>= 0).
    Eigen::MatrixXd zscore;      ///< N by D: residual / sqrt(variance) (0 where the variance is 0).
    double mse = 0.0;            ///< mean of residual^2 over all entries (the paper's MSE for D = 1).
};

/// The O(M^3) part of Kriging::build: the inverse of the covariance matrix of the M unique control
/// points, robustly factorized (jitter, regularization: see the header comment), and how. A caller that
/// builds the same system again (same points, model and options) hands it back to build(), which then
/// costs O(M^2 K): synthesis stores it with a set's kernel (synthesis/kernel_fit.hpp).
struct CovarianceInverse {
    Eigen::MatrixXd inverse;  ///< M by M
    FactorizationStatus factorization = FactorizationStatus::Ok;
    double jitter = 0.0;
    double rcond = 0.0;
};

class KrigingPredictor;
class LocalKriging;

class Kriging final : public Interpolator {
public:
    Kriging() = default;

    /// coords: N by P control points (N >= 1, finite). Throws InvalidArgument on bad shapes, non-finite
    /// coordinates, an invalid model, a model with nugget + sill == 0, or out-of-range options.
    static Kriging build(const Eigen::Ref<const Eigen::MatrixXd>& coords, const VariogramModel& model,
                         const KrigingOptions& options = {});
    /// The same with the covariance inverse of these inputs precomputed (covariance_inverse()); one of
    /// another size (or null) is ignored and the system factorized as without it, reporting to progress
    /// (may be empty) as covariance_inverse() does.
    static Kriging build(const Eigen::Ref<const Eigen::MatrixXd>& coords, const VariogramModel& model,
                         const KrigingOptions& options, const CovarianceInverse* precomputed,
                         const ProgressCallback& progress = {});
    /// What build() factorizes (same errors); O(M^3) time, O(M^2) memory. progress (may be empty): called
    /// with item "kernel system" as blocks of the inverse's columns are done (done / total columns).
    static CovarianceInverse covariance_inverse(const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                                const VariogramModel& model, const KrigingOptions& options = {},
                                                const ProgressCallback& progress = {});

    Eigen::Index num_samples() const override { return group_.size(); }
    Eigen::Index dimension() const override { return points_.cols(); }

    /// w(c): c P, out_weights N. No allocation once the workspace has grown.
    void weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                 QueryWorkspace& workspace) const override;
    /// W: queries Q by P, out_weights N by Q.
    void weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                       Eigen::Ref<Eigen::MatrixXd> out_weights) const override;
    using Interpolator::weights;
    using Interpolator::weights_batch;

    /// All outputs at one query (c: P).
    KrigingEstimate estimate(const Eigen::Ref<const Eigen::VectorXd>& c) const;
    /// All outputs at Q queries (queries: Q by P).
    KrigingBatch estimate_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const;
    /// rho at Q queries (queries: Q by P); returns Q.
    Eigen::VectorXd reliability(const Eigen::Ref<const Eigen::MatrixXd>& queries) const;

    /// Closed-form leave-one-out. values: N by D. A sample that has merged duplicates is predicted by the
    /// mean of its duplicates (exact interpolation), with variance 0.
    LooResult leave_one_out(const Eigen::Ref<const Eigen::MatrixXd>& values) const;
    /// Reliability rho(c_i) of every sample computed without it (paper Section 5.2): N. A sample with a
    /// merged duplicate has reliability 1.
    /// With ReliabilityVariance::Prediction this is 1 - V_i / total sill with V_i the variance of the
    /// left-out prediction (for OLS: of the ordinary kriging of the residuals; filtered: minus the nugget).
    Eigen::VectorXd leave_one_out_reliability() const;

    const VariogramModel& model() const { return model_; }
    const KrigingOptions& options() const { return options_; }
    const KrigingStatus& status() const { return status_; }
    const TrendBasis& trend_basis() const { return basis_; }
    /// Unique control points (M by P) and, for each of the N samples, the index of its unique point.
    const Eigen::MatrixXd& unique_points() const { return points_; }
    const Eigen::VectorXi& unique_index() const { return group_; }

    // Internal access for the reduction module (covariance-form data block of the inverse system,
    // M by M, and the variogram matrix of the unique points, M by M).
    const Eigen::MatrixXd& data_block_inverse() const { return kernel_inverse_; }
    const Eigen::MatrixXd& gamma_matrix() const { return gamma_; }

private:
    // build() up to the unique points (validation, duplicates, trend basis).
    static Kriging prepare(const Eigen::Ref<const Eigen::MatrixXd>& coords, const VariogramModel& model,
                           const KrigingOptions& options);
    friend class KrigingPredictor;  // folds sample values into weight_operator() (kriging_predictor.hpp)
    friend class LocalKriging;      // prepares its points as build() does (local_kriging.hpp)

    // gamma of the query (the continuous part only when filtering the nugget): out M.
    void gamma_vector(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out) const;
    void gamma_block(const Eigen::Ref<const Eigen::MatrixXd>& queries, Eigen::Ref<Eigen::MatrixXd> out) const;
    // From gamma (M by Q) and trend basis values (K by Q): kernel b (M by Q) and weights w (M by Q).
    void solve_block(const Eigen::Ref<const Eigen::MatrixXd>& gamma, const Eigen::Ref<const Eigen::MatrixXd>& g,
                     Eigen::MatrixXd& out_kernel, Eigen::MatrixXd& out_weights) const;
    // The operator of the weights: w = weight_operator() [gamma(c); g(c)] (M by M + K), before the
    // constraint projection. GLS / OK: operator_ itself; OLS: weight_operator_.
    const Eigen::MatrixXd& weight_operator() const;
    // rhs = [gamma; g] (M + K by Q) to weights on the unique points (out: M by Q); scratch: any size.
    void weights_from_rhs(const Eigen::Ref<const Eigen::MatrixXd>& rhs, Eigen::Ref<Eigen::MatrixXd> out,
                          Eigen::MatrixXd& scratch) const;

    VariogramModel model_;
    VariogramModel query_model_;  // model_, or model_ without its nugget when filtering (query vectors)
    KrigingOptions options_;
    KrigingStatus status_;
    TrendBasis basis_;            // over the unique points
    Eigen::MatrixXd points_;      // M by P unique control points
    Eigen::VectorXi group_;       // N -> unique index
    Eigen::VectorXd group_size_;  // M
    bool merged_ = false;
    Eigen::MatrixXd gamma_;  // M by M variogram matrix (diagonal 0)
    // Kernel system (GLS/OK: the full trend basis; OLS: only the constant):
    //   b = -Wc gamma(c) + V g_k(c), from kernel_inverse_ and v_transpose_; GLS / OK also keep it as
    //   operator_ = [-Wc, V] (M by M + K_k), their weight operator (empty for OLS).
    Eigen::MatrixXd operator_;
    Eigen::MatrixXd kernel_inverse_;  // Wc (M by M)
    Eigen::MatrixXd v_transpose_;     // V^T (K_k by M)
    Eigen::MatrixXd s_inverse_;       // (F^T C^-1 F)^-1 (K_k by K_k)
    Eigen::Index kernel_trend_size_ = 1;
    Eigen::MatrixXd ols_u_;  // OLS only: M by r orthonormal trend columns (basis_ without the constant)
    // OLS only (empty otherwise): weights w = b + U (g_u(c) - U^T b) as one operator on [gamma(c); g(c)],
    //   [(I - U U^T) operator_, U]  (M by M + 1 + r), so a query is a single matrix-vector product.
    Eigen::MatrixXd weight_operator_;
    // Single queries with AVX2 + FMA (null otherwise): -Wc packed as its lower block triangle (half the
    // bytes of operator_), V and the trend basis, in the layout of the vector kernels of `weights`
    // (internal, lib/src/kriging/query_kernels.hpp). Immutable, so shared by copies.
    std::shared_ptr<const detail::QueryOperator> query_operator_;
};

}  // namespace mocapdb::kriging
