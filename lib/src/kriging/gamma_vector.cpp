#include "gamma_vector.hpp"

namespace mocapdb::kriging::detail {

void gamma_vector(const Eigen::MatrixXd& points, const VariogramModel& model, const Eigen::Ref<const Eigen::VectorXd>& c,
                  Eigen::Ref<Eigen::VectorXd> out) {
    const Eigen::Index p = points.cols();
    out = (points.col(0).array() - c(0)).square().matrix();
    for (Eigen::Index d = 1; d < p; ++d) out.array() += (points.col(d).array() - c(d)).square();
    model.gamma_of_squared(out, out);
}

void gamma_block(const Eigen::MatrixXd& points, const VariogramModel& model,
                 const Eigen::Ref<const Eigen::MatrixXd>& queries, Eigen::Ref<Eigen::MatrixXd> out) {
    // Squared distances column by column (one query per column of out), then gamma on the whole block.
    const Eigen::Index p = points.cols();
    for (Eigen::Index q = 0; q < queries.rows(); ++q) {
        auto col = out.col(q).array();
        col = (points.col(0).array() - queries(q, 0)).square();
        for (Eigen::Index d = 1; d < p; ++d) col += (points.col(d).array() - queries(q, d)).square();
    }
    if (out.outerStride() == out.rows()) {
        const Eigen::Map<const Eigen::VectorXd> flat_in(out.data(), out.size());
        Eigen::Map<Eigen::VectorXd> flat_out(out.data(), out.size());
        model.gamma_of_squared(flat_in, flat_out);
    } else {
        for (Eigen::Index q = 0; q < out.cols(); ++q) model.gamma_of_squared(out.col(q), out.col(q));
    }
}

}  // namespace mocapdb::kriging::detail
