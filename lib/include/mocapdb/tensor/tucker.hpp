#pragma once
// The Tucker model of a D by T by N motion tensor A:
//     A ~ A_hat = G x_0 U_dof x_1 U_time x_2 U_sample,
// core G (R1 by R2 by R3), orthonormal bases U_dof (D by R1), U_time (T by R2), U_sample (N by R3).
// A pose (a D-vector) at a time coefficient row u_time (1 by R2, a row of U_time or an interpolation
// of rows) and a sample coefficient row u_sample (1 by R3, a row of U_sample or a kriged estimate) is
//     q = G x_0 U_dof x_1 u_time x_2 u_sample.
// Level of detail: using only the first (r1, r2, r3) columns of the bases and the matching leading
// block of the core; the columns are ordered by decreasing singular value, so a prefix is the
// truncated model of lower rank (exactly so for HOSVD).
//
// Details: docs/headers/tensor.md (mocapdb/tensor/tucker.hpp).
#include <array>
#include <vector>

#include <Eigen/Core>

#include "mocapdb/tensor/unfold.hpp"

namespace mocapdb::tensor {

enum class TuckerMethod {
    Hosvd,    ///< truncated higher-order SVD (each basis from the Gram matrix of A_(n))
    StHosvd,  ///< sequentially truncated HOSVD (each basis from the already-projected tensor)
    Hooi      ///< higher-order orthogonal iteration, started from the truncated HOSVD
};

/// Numerical outcome of a decomposition (never thrown).
enum class TuckerStatus {
    Ok,             ///< direct method (HOSVD, ST-HOSVD) finished
    Converged,      ///< HOOI: relative fit change fell below the tolerance
    MaxIterations,  ///< HOOI: stopped at max_iterations before reaching the tolerance
    Stalled         ///< HOOI: a sweep lowered the fit (rounding); the best model seen is returned
};

const char* to_string(TuckerMethod method);
const char* to_string(TuckerStatus status);

/// Eigenvalues of the three mode Gram matrices A_(n) A_(n)^T (= squared singular values of the
/// unfoldings), each sorted in decreasing order and clamped at 0.
struct ModeSpectra {
    Dims3 dims{0, 0, 0};             ///< (I0, I1, I2) of the tensor
    std::array<VecX, 3> squared_sv;  ///< squared_sv[n]: I_n entries, decreasing, >= 0
    double squared_norm = 0.0;       ///< ||A||_F^2 (= the trace of every Gram matrix)
};

/// sqrt( sum_n sum_{i >= ranks[n]} squared_sv[n](i) ): the HOSVD bound on ||A - A_hat||_F (absolute).
/// ranks: 0 <= ranks[n] <= dims[n]. Throws InvalidArgument otherwise.
double hosvd_error_bound(const ModeSpectra& spectra, const Ranks& ranks);

/// Number of stored values of a Tucker model: R1 R2 R3 + D R1 + T R2 + N R3.
Eigen::Index tucker_parameter_count(const Dims3& dims, const Ranks& ranks);

/// D T N / tucker_parameter_count(dims, ranks).
double tucker_compression_ratio(const Dims3& dims, const Ranks& ranks);

/// Throws InvalidArgument unless every dimension is >= 1 and 1 <= ranks[n] <= dims[n]; `where` names
/// the calling function in the message.
void check_ranks(const Dims3& dims, const Ranks& ranks, const char* where);

/// Throws InvalidArgument unless a has no zero dimension and every element is finite.
void check_tensor(const Tensor3& a, const char* where);

/// A decomposed tensor. Plain data: build it with hosvd(), st_hosvd() or hooi().
struct TuckerModel {
    Tensor3 core;           ///< R1 by R2 by R3
    std::array<MatX, 3> U;  ///< U[0]: D by R1 (dof), U[1]: T by R2 (time), U[2]: N by R3 (sample); orthonormal columns
    Ranks ranks{0, 0, 0};   ///< (R1, R2, R3)
    TuckerMethod method = TuckerMethod::Hosvd;
    int iterations = 0;  ///< HOOI sweeps performed (0 for HOSVD and ST-HOSVD)
    /// 1 - ||A - A_hat||_F / ||A||_F, from the orthogonality identity ||A - A_hat||^2 = ||A||^2 - ||G||^2
    /// (accurate to about 1e-8 relative error; relative_error() measures by reconstruction).
    double fit = 0.0;
    TuckerStatus status = TuckerStatus::Ok;
    double data_norm = 0.0;  ///< ||A||_F of the decomposed tensor
    /// Upper bound on ||A - A_hat||_F (absolute). HOSVD: the discarded-singular-value bound above;
    /// ST-HOSVD: sqrt of the energy discarded at each sequential step (equal to the error in exact
    /// arithmetic, and <= the HOSVD bound); HOOI: the bound of its HOSVD start (HOOI is never worse).
    double error_bound = 0.0;
    /// HOOI: fit of the start (entry 0) and after each sweep; HOSVD, ST-HOSVD: the one fit.
    std::vector<double> fit_history;

    Dims3 dims() const { return {U[0].rows(), U[1].rows(), U[2].rows()}; }

    /// The full reconstruction A_hat: D by T by N.
    Tensor3 reconstruct() const;
    /// Reconstruction at a level of detail: lod = (r1, r2, r3), 1 <= r_n <= ranks[n]. D by T by N.
    Tensor3 reconstruct(const Ranks& lod) const;
    /// One sample's motion: D by T, equal to reconstruct() sliced at sample n. 0 <= n < N.
    MatX reconstruct_sample(Eigen::Index n) const;

    /// The pose at stored time t (0 <= t < T) and sample n (0 <= n < N): D-vector, equal to the fibre
    /// reconstruct()(:, t, n).
    VecX pose(Eigen::Index t, Eigen::Index n) const;
    /// The pose at coefficient rows. u_time: 1 by R2; u_sample: 1 by R3. Returns a D-vector.
    VecX pose(const Eigen::Ref<const Eigen::RowVectorXd>& u_time,
              const Eigen::Ref<const Eigen::RowVectorXd>& u_sample) const;
    /// The pose at a level of detail lod = (r1, r2, r3), 1 <= r_n <= ranks[n]: only the first r2
    /// entries of u_time (1 by R2) and the first r3 of u_sample (1 by R3) are used. Returns a D-vector.
    VecX pose(const Eigen::Ref<const Eigen::RowVectorXd>& u_time, const Eigen::Ref<const Eigen::RowVectorXd>& u_sample,
              const Ranks& lod) const;

    /// tucker_parameter_count(dims(), ranks) and tucker_compression_ratio(dims(), ranks).
    Eigen::Index parameter_count() const;
    double compression_ratio() const;
    /// ||A - A_hat||_F / ||A||_F from the fit (1 - fit).
    double relative_error_estimate() const { return 1.0 - fit; }
};

/// The model truncated to a level of detail lod (1 <= lod[n] <= model.ranks[n]): leading core block
/// and basis prefixes. For a HOSVD model this is exactly the HOSVD at ranks lod. The fit, bound and
/// history are NOT recomputed (they need the data); the caller may refresh them.
TuckerModel truncate(const TuckerModel& model, const Ranks& lod);

/// Measured ||a - model.reconstruct()||_F / ||a||_F by explicit reconstruction (0 when a is zero
/// and so is the reconstruction). a: D by T by N matching model.dims(). Throws InvalidArgument on
/// a shape mismatch.
double relative_error(const Tensor3& a, const TuckerModel& model);

/// Measured ||a - model.reconstruct()||_F (absolute). Same shapes as relative_error.
double absolute_error(const Tensor3& a, const TuckerModel& model);

/// Fast pose synthesis for one level of detail (immutable after construction, thread-safe).
/// Two evaluation orders, same result up to rounding:
///  - DofPrecomputed: W = U_dof * G_(0), a D by (r2 r3) matrix precomputed; a pose is
///    W * (u_sample (x) u_time): D r2 r3 multiply-adds.
///  - CoreFirst: contract the core with u_sample then u_time, then multiply by U_dof:
///    r1 r2 r3 + r1 r2 + D r1 multiply-adds.
/// Auto picks the one with fewer multiply-adds.
class PoseEvaluator {
public:
    enum class Order { Auto, DofPrecomputed, CoreFirst };

    /// model: any TuckerModel; lod: 1 <= lod[n] <= model.ranks[n]. Throws InvalidArgument otherwise.
    PoseEvaluator(const TuckerModel& model, const Ranks& lod, Order order = Order::Auto);
    /// The full ranks of the model.
    explicit PoseEvaluator(const TuckerModel& model, Order order = Order::Auto);

    Eigen::Index dofs() const { return dofs_; }
    const Ranks& ranks() const { return lod_; }
    Order order() const { return order_; }

    /// Scratch memory owned by the caller (one per thread); sized on first use, then reused.
    struct Workspace {
        VecX buffer;
    };

    /// u_time: at least r2 entries (first r2 used); u_sample: at least r3 entries (first r3 used);
    /// out_pose: D entries, overwritten. No heap allocation once ws has been sized.
    /// Throws InvalidArgument on short inputs or a wrong out_pose size.
    void evaluate(const Eigen::Ref<const Eigen::RowVectorXd>& u_time,
                  const Eigen::Ref<const Eigen::RowVectorXd>& u_sample, Eigen::Ref<VecX> out_pose, Workspace& ws) const;
    /// Convenience: allocating form. Returns a D-vector.
    VecX evaluate(const Eigen::Ref<const Eigen::RowVectorXd>& u_time,
                  const Eigen::Ref<const Eigen::RowVectorXd>& u_sample) const;

private:
    Eigen::Index dofs_ = 0;
    Ranks lod_{0, 0, 0};
    Order order_ = Order::CoreFirst;
    MatX w_;      ///< DofPrecomputed: D by (r2 r3), column j + r2 k.
    MatX core_;   ///< CoreFirst: (r1 r2) by r3, the leading core block in storage order.
    MatX u_dof_;  ///< CoreFirst: D by r1.
};

}  // namespace mocapdb::tensor
