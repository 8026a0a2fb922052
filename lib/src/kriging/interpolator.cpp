#include "mocapdb/kriging/interpolator.hpp"

#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb::kriging {

Eigen::VectorXd Interpolator::weights(const Eigen::Ref<const Eigen::VectorXd>& c) const {
    Eigen::VectorXd w(num_samples());
    QueryWorkspace ws;
    weights(c, w, ws);
    return w;
}

Eigen::MatrixXd Interpolator::weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const {
    Eigen::MatrixXd w(num_samples(), queries.rows());
    weights_batch(queries, w);
    return w;
}

Eigen::MatrixXd Interpolator::predict(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                                      const Eigen::Ref<const Eigen::MatrixXd>& values) const {
    if (values.rows() != num_samples()) {
        throw InvalidArgument("Interpolator::predict: values must be N by D with N = " + std::to_string(num_samples()) +
                              ", got " + std::to_string(values.rows()) + " rows");
    }
    const Eigen::MatrixXd w = weights_batch(queries);
    Eigen::MatrixXd out(queries.rows(), values.cols());
    out.noalias() = w.transpose() * values;
    return out;
}

}  // namespace mocapdb::kriging
