#pragma once
// Internal (not installed): variogram values between control points and queries, shared by Kriging and
// KrigingPredictor. Squared distances by one vectorized pass per coordinate, then the model on the whole
// vector or block at once (VariogramModel::gamma_of_squared).
#include <Eigen/Core>

#include "mocapdb/kriging/variogram_model.hpp"

namespace mocapdb::kriging::detail {

/// out(i) = gamma(|points.row(i) - c|). points: M by P (a block of rows of a matrix too); c: P; out: M.
void gamma_vector(const Eigen::Ref<const Eigen::MatrixXd>& points, const VariogramModel& model,
                  const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out);

/// out(i, q) = gamma(|points.row(i) - queries.row(q)|). points: M by P; queries: Q by P; out: M by Q.
void gamma_block(const Eigen::MatrixXd& points, const VariogramModel& model,
                 const Eigen::Ref<const Eigen::MatrixXd>& queries, Eigen::Ref<Eigen::MatrixXd> out);

}  // namespace mocapdb::kriging::detail
