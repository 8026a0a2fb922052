#pragma once
// Kriging of whole motions on plain Eigen inputs, with the kernel variants of the paper, selectable.
//
// Details: docs/headers/kriging.md (mocapdb/kriging/motion_kriging.hpp).
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "mocapdb/kriging/interpolator.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/rbf.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "mocapdb/kriging/variogram_fit.hpp"

namespace mocapdb::kriging {

enum class KernelScope { PerElement, PerPose, PerSet };
enum class InterpolationMethod { Kriging, Rbf };

const char* to_string(KernelScope scope);

struct MotionKrigingOptions {
    KernelScope scope = KernelScope::PerPose;
    InterpolationMethod method = InterpolationMethod::Kriging;
    Eigen::Index dofs_per_frame = 0;      ///< D >= 1 for PerElement / PerPose (must divide the columns); 0 = one frame.
    std::vector<Eigen::Index> root_dofs;  ///< PerPose: dofs in [0, D) kriged per element (e.g. 0,1,2 and heading).
    bool normalize_controls = true;
    std::optional<ControlScaling> scaling;  ///< overrides the automatic per-axis scaling.
    std::optional<double> exponent;         ///< fixed p (0 = spherical); otherwise chosen by LOO.
    Eigen::Index representative = -1;       ///< column (PerElement) or frame (PerPose) for choosing p; -1 = automatic.
    VariogramOptions variogram;
    VariogramFitOptions fit;
    KrigingOptions kriging;
    RbfOptions rbf;
};

/// Summary of what was built.
struct MotionKrigingReport {
    double exponent = 0.0;                ///< p used for all kernels (paper convention); PerPose: the pose kernels'.
    double root_exponent = 0.0;           ///< PerPose: p of the root dofs' per-element kernels (chosen on their own).
    Eigen::Index kernels = 0;             ///< number of kernels.
    Eigen::Index degenerate_kernels = 0;  ///< signals without variation (placeholder model; weights still valid).
    Eigen::Index inexact_kernels = 0;     ///< kernels whose factorization needed jitter or regularization.
    Eigen::Index duplicates_merged = 0;
    bool trend_rank_deficient = false;
};

class MotionKriging {
public:
    MotionKriging() = default;

    /// coords: N by P; samples: N by (D*T) (or N by M for PerSet); pose_signal: N by T (PerPose, else may be
    /// empty); dissimilarity: N by N symmetric (PerSet, optional: empty = Euclidean on residual rows).
    /// Throws InvalidArgument on inconsistent shapes, non-finite input or invalid options.
    static MotionKriging build(const Eigen::Ref<const Eigen::MatrixXd>& coords,
                               const Eigen::Ref<const Eigen::MatrixXd>& samples,
                               const Eigen::Ref<const Eigen::MatrixXd>& pose_signal,
                               const Eigen::Ref<const Eigen::MatrixXd>& dissimilarity,
                               const MotionKrigingOptions& options);

    Eigen::Index num_samples() const { return samples_.rows(); }
    Eigen::Index dimension() const { return scaling_.scale.size(); }
    Eigen::Index num_columns() const { return samples_.cols(); }

    /// Prediction at one query: c P, out_values D*T (or M).
    void predict(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_values) const;
    /// Predictions at Q queries: queries Q by P; returns Q by (D*T).
    Eigen::MatrixXd predict_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const;

    /// Kernel k (0 <= k < report().kernels) and the kernel index of every column (D*T).
    const Interpolator& kernel(Eigen::Index k) const { return *kernels_.at(static_cast<std::size_t>(k)); }
    const std::vector<Eigen::Index>& kernel_of_column() const { return kernel_of_column_; }
    /// Variogram model of kernel k (Kriging only; empty for Rbf).
    const std::vector<VariogramModel>& models() const { return models_; }
    const MotionKrigingReport& report() const { return report_; }
    const ControlScaling& scaling() const { return scaling_; }

private:
    ControlScaling scaling_;
    Eigen::MatrixXd samples_;  // N by (D*T)
    std::vector<std::shared_ptr<const Interpolator>> kernels_;
    std::vector<Eigen::Index> kernel_of_column_;
    std::vector<std::vector<Eigen::Index>> columns_of_kernel_;
    std::vector<VariogramModel> models_;
    MotionKrigingReport report_;
};

}  // namespace mocapdb::kriging
