#include "mocapdb/synthesis/predictor_choice.hpp"

#include <cmath>
#include <cstdio>
#include <memory>

#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/trend_interpolator.hpp"

namespace mocapdb::synthesis {
namespace {

// At most `count` of 0 .. n - 1, evenly spread (all of them when count >= n).
std::vector<Eigen::Index> spread_rows(Eigen::Index n, std::size_t count) {
    std::vector<Eigen::Index> out;
    const auto m = std::min<Eigen::Index>(n, static_cast<Eigen::Index>(count));
    if (m == 1) return {0};
    const double step = static_cast<double>(n - 1) / static_cast<double>(m - 1);
    for (Eigen::Index i = 0; i < m; ++i)
        out.push_back(static_cast<Eigen::Index>(std::lround(step * static_cast<double>(i))));
    return out;
}

std::unique_ptr<kriging::Interpolator> build_predictor(Predictor p, const MatX& x,
                                                       const kriging::VariogramModel& variogram,
                                                       const kriging::KrigingOptions& kriging,
                                                       const kriging::RbfOptions& rbf) {
    switch (p) {
        case Predictor::Kriging:
            return std::make_unique<kriging::Kriging>(kriging::Kriging::build(x, variogram, kriging));
        case Predictor::Rbf: return std::make_unique<kriging::RbfInterpolator>(kriging::RbfInterpolator::build(x, rbf));
        case Predictor::Trend:
            return std::make_unique<kriging::TrendInterpolator>(
                kriging::TrendInterpolator::build(x, kriging.trend, kriging.trend_rank_tolerance));
    }
    throw InvalidArgument("choose_predictor: unknown predictor");
}

}  // namespace

const char* to_string(Predictor predictor) {
    switch (predictor) {
        case Predictor::Kriging: return "kriging";
        case Predictor::Rbf: return "rbf";
        case Predictor::Trend: return "trend";
    }
    return "unknown";
}

std::optional<Predictor> parse_predictor(const std::string& name) {
    for (const Predictor p : all_predictors())
        if (name == to_string(p)) return p;
    return std::nullopt;
}

const std::vector<Predictor>& all_predictors() {
    static const std::vector<Predictor> all = {Predictor::Kriging, Predictor::Rbf, Predictor::Trend};
    return all;
}

PredictorChoice choose_predictor(const Eigen::Ref<const MatX>& xc, const Eigen::Ref<const MatX>& values,
                                 const kriging::VariogramModel& variogram, const kriging::KrigingOptions& kriging,
                                 const std::vector<std::vector<std::size_t>>& twins,
                                 const PredictorChoiceOptions& options) {
    const char* where = "predictor choice";
    const Eigen::Index n_all = xc.rows();
    if (values.rows() != n_all || !values.allFinite() || !xc.allFinite())
        throw InvalidArgument(std::string(where) + ": values must be N by S and finite, with N = " +
                              std::to_string(n_all) + " control points");
    if (options.folds < 1 || options.max_samples < 5 || !(options.elements_per_sample > 0.0))
        throw InvalidArgument(std::string(where) + ": folds must be >= 1, max_samples >= 5, elements per sample > 0");

    if (!twins.empty() && static_cast<Eigen::Index>(twins.size()) != n_all)
        throw InvalidArgument(std::string(where) + ": twins must be empty or one list per sample");
    // The rows the choice sees, and each one's twins among them (as local indices).
    const std::vector<Eigen::Index> rows = spread_rows(n_all, options.max_samples);
    const auto n = static_cast<Eigen::Index>(rows.size());
    std::vector<Eigen::Index> local(static_cast<std::size_t>(n_all), -1);
    for (Eigen::Index k = 0; k < n; ++k) local[static_cast<std::size_t>(rows[static_cast<std::size_t>(k)])] = k;
    std::vector<std::vector<Eigen::Index>> twins_of(static_cast<std::size_t>(n));
    for (Eigen::Index k = 0; k < n && !twins.empty(); ++k) {
        for (const std::size_t s : twins[static_cast<std::size_t>(rows[static_cast<std::size_t>(k)])]) {
            if (s >= static_cast<std::size_t>(n_all))
                throw InvalidArgument(std::string(where) + ": a twin index is out of range");
            if (local[s] >= 0) twins_of[static_cast<std::size_t>(k)].push_back(local[s]);
        }
    }
    MatX x(n, xc.cols()), v(n, values.cols());
    for (Eigen::Index k = 0; k < n; ++k) {
        x.row(k) = xc.row(rows[static_cast<std::size_t>(k)]);
        v.row(k) = values.row(rows[static_cast<std::size_t>(k)]);
    }

    const std::vector<Predictor>& predictors = options.candidates;
    if (predictors.empty()) throw InvalidArgument(std::string(where) + ": no candidate predictor");
    VecX sum = VecX::Zero(static_cast<Eigen::Index>(predictors.size()));
    PredictorChoice out;
    out.samples = static_cast<std::size_t>(n);
    kriging::QueryWorkspace ws;
    for (const Eigen::Index i : spread_rows(n, options.folds)) {
        std::vector<bool> out_of_training(static_cast<std::size_t>(n), false);
        out_of_training[static_cast<std::size_t>(i)] = true;
        for (const Eigen::Index t : twins_of[static_cast<std::size_t>(i)])
            out_of_training[static_cast<std::size_t>(t)] = true;
        std::vector<Eigen::Index> train;
        for (Eigen::Index k = 0; k < n; ++k)
            if (!out_of_training[static_cast<std::size_t>(k)]) train.push_back(k);
        if (train.size() < 3) continue;
        const auto m = static_cast<Eigen::Index>(train.size());
        MatX xt(m, x.cols()), vt(m, v.cols());
        for (Eigen::Index k = 0; k < m; ++k) {
            xt.row(k) = x.row(train[static_cast<std::size_t>(k)]);
            vt.row(k) = v.row(train[static_cast<std::size_t>(k)]);
        }
        const VecX target = v.row(i).transpose();
        const VecX query = x.row(i).transpose();
        VecX w(m);
        for (std::size_t p = 0; p < predictors.size(); ++p) {
            const auto interpolator = build_predictor(predictors[p], xt, variogram, kriging, options.rbf);
            interpolator->weights(query, w, ws);
            const double squared = (vt.transpose() * w - target).squaredNorm();
            sum(static_cast<Eigen::Index>(p)) += std::sqrt(squared / options.elements_per_sample);
        }
        ++out.folds;
    }
    if (out.folds == 0) return out;
    std::size_t best = 0;
    for (std::size_t p = 0; p < predictors.size(); ++p) {
        const double cv = sum(static_cast<Eigen::Index>(p)) / static_cast<double>(out.folds);
        if (p == 0 || cv < out.scores[best].cv_rms) best = p;
        out.scores.push_back({predictors[p], cv});
    }
    out.chosen = predictors[best];
    return out;
}

std::string describe(const PredictorChoice& choice) {
    if (choice.folds == 0) return std::string(to_string(choice.chosen)) + " (no fold could be left out)";
    char buf[64];
    std::string chosen, others;
    for (const PredictorScore& score : choice.scores) {
        std::snprintf(buf, sizeof buf, "%.3g", score.cv_rms);
        if (score.predictor == choice.chosen) chosen = buf;
        else others += std::string(", ") + to_string(score.predictor) + " " + buf;
    }
    return std::string(to_string(choice.chosen)) + " (cv " + chosen + others + "; " + std::to_string(choice.folds) +
           " folds of " + std::to_string(choice.samples) + " samples)";
}

}  // namespace mocapdb::synthesis
