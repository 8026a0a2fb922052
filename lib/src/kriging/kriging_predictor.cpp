#include "mocapdb/kriging/kriging_predictor.hpp"

#include <algorithm>
#include <string>

#include "mocapdb/core/error.hpp"
#include "gamma_vector.hpp"

namespace mocapdb::kriging {

KrigingPredictor KrigingPredictor::build(const Kriging& kriging, const Eigen::Ref<const Eigen::MatrixXd>& values) {
    const Eigen::Index n = kriging.num_samples();
    if (n < 1) throw InvalidArgument("KrigingPredictor::build: the kriging object is empty (not built)");
    if (values.rows() != n || values.cols() < 1) {
        throw InvalidArgument("KrigingPredictor::build: values must be N by S with N = " + std::to_string(n) +
                              " and S >= 1, got " + std::to_string(values.rows()) + "x" +
                              std::to_string(values.cols()));
    }
    if (!values.allFinite()) throw InvalidArgument("KrigingPredictor::build: values must be finite");
    KrigingPredictor kp;
    kp.model_ = kriging.query_model_;  // the query vectors (filtered: without the nugget)
    kp.basis_ = kriging.basis_;
    kp.points_ = kriging.points_;
    kp.num_samples_ = n;
    const Eigen::Index m = kriging.points_.rows();
    const Eigen::Index kk = kriging.basis_.size();
    const Eigen::Index s = values.cols();
    // Vm = E^T V (M by S): the values of each unique point's samples, each weighted 1 / group size.
    Eigen::MatrixXd vm = Eigen::MatrixXd::Zero(m, s);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Index u = kriging.group_(i);
        vm.row(u) += values.row(i) / kriging.group_size_(u);
    }
    // (E^T V)^T G D and P Vm = Vm - G D G^T Vm.
    const Eigen::MatrixXd& gb = kriging.basis_.sample_basis();
    Eigen::MatrixXd gtv(kk, s);
    gtv.noalias() = gb.transpose() * vm;
    gtv.row(0) /= static_cast<double>(m);  // D G^T Vm
    Eigen::MatrixXd pvm = vm;
    pvm.noalias() -= gb * gtv;
    const Eigen::MatrixXd& op = kriging.weight_operator();
    kp.folded_.resize(s, m + kk);
    kp.folded_.noalias() = pvm.transpose() * op;
    kp.folded_.rightCols(kk) += gtv.transpose();  // (D G^T Vm)^T = Vm^T G D
    return kp;
}

void KrigingPredictor::predict(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out,
                               QueryWorkspace& ws) const {
    if (c.size() != dimension() || out.size() != output_size()) {
        throw InvalidArgument("KrigingPredictor::predict: c must have P = " + std::to_string(dimension()) +
                              " entries and out S = " + std::to_string(output_size()));
    }
    const Eigen::Index m = points_.rows();
    const Eigen::Index kk = basis_.size();
    if (ws.rhs.size() != m + kk) ws.rhs.resize(m + kk);
    detail::gamma_vector(points_, model_, c, ws.rhs.head(m));
    basis_.evaluate(c, ws.rhs.tail(kk));
    out.noalias() = folded_ * ws.rhs;
}

namespace {
constexpr Eigen::Index kQueriesPerProduct = 256;  // queries per matrix product (as Kriging::weights_batch)
}  // namespace

void KrigingPredictor::predict_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries, Eigen::Ref<Eigen::MatrixXd> out,
                                     Eigen::MatrixXd& scratch) const {
    if (queries.cols() != dimension() || out.rows() != output_size() || out.cols() != queries.rows()) {
        throw InvalidArgument(
            "KrigingPredictor::predict_batch: queries must be Q by P (P = " + std::to_string(dimension()) +
            ") and out S by Q (S = " + std::to_string(output_size()) + ")");
    }
    const Eigen::Index m = points_.rows();
    const Eigen::Index kk = basis_.size();
    const Eigen::Index block = std::min(kQueriesPerProduct, queries.rows());
    if (scratch.rows() != m + kk || scratch.cols() != block) scratch.resize(m + kk, block);
    for (Eigen::Index q0 = 0; q0 < queries.rows(); q0 += kQueriesPerProduct) {
        const Eigen::Index nb = std::min(kQueriesPerProduct, queries.rows() - q0);
        auto rhs = scratch.leftCols(nb);
        detail::gamma_block(points_, model_, queries.middleRows(q0, nb), rhs.topRows(m));
        rhs.bottomRows(kk) = basis_.evaluate_batch(queries.middleRows(q0, nb));
        out.middleCols(q0, nb).noalias() = folded_ * rhs;
    }
}

Eigen::MatrixXd KrigingPredictor::predict_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const {
    Eigen::MatrixXd out(output_size(), queries.rows());
    Eigen::MatrixXd scratch;
    predict_batch(queries, out, scratch);
    return out;
}

}  // namespace mocapdb::kriging
