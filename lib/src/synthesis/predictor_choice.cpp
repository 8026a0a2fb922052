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
        case Predictor::Average: break;
    }
    throw InvalidArgument("choose_predictor: the average is a choice, not a candidate");
}

}  // namespace

const char* to_string(Predictor predictor) {
    switch (predictor) {
        case Predictor::Kriging: return "kriging";
        case Predictor::Rbf: return "rbf";
        case Predictor::Trend: return "trend";
        case Predictor::Average: return "average";
    }
    return "unknown";
}

std::optional<Predictor> parse_predictor(const std::string& name) {
    for (const Predictor p : all_predictors())
        if (name == to_string(p)) return p;
    if (name == to_string(Predictor::Average)) return Predictor::Average;
    return std::nullopt;
}

std::vector<Predictor> PredictorChoice::members() const {
    std::vector<Predictor> out;
    for (const PredictorScore& s : scores)
        if (s.weight > 0.0) out.push_back(s.predictor);
    if (out.empty()) out.push_back(chosen == Predictor::Average ? Predictor::Kriging : chosen);
    return out;
}

MatX posture_values(const Eigen::Ref<const MatX>& weighted_rows, Eigen::Index dofs) {
    if (dofs <= kRootPathDofs.back() || weighted_rows.cols() % dofs != 0)
        throw InvalidArgument("posture values: the rows must hold whole pose vectors of " + std::to_string(dofs) +
                              " dofs (more than " + std::to_string(kRootPathDofs.back()) + ")");
    MatX out = weighted_rows;
    for (Eigen::Index t = 0; t < out.cols() / dofs; ++t)
        for (const Eigen::Index k : kRootPathDofs) out.col(t * dofs + k).setZero();
    return out;
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
    if (options.folds < 1 || options.max_samples < 5 || !(options.elements_per_sample > 0.0) ||
        !(options.average_within_se >= 0.0))
        throw InvalidArgument(
            std::string(where) +
            ": folds must be >= 1, max_samples >= 5, elements per sample > 0, average_within_se >= 0");

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
    for (const Predictor p : predictors)
        if (p == Predictor::Average) throw InvalidArgument(std::string(where) + ": the average is not a candidate");
    std::vector<std::vector<double>> errors(predictors.size());  // per candidate, per fold
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
            errors[p].push_back(std::sqrt(squared / options.elements_per_sample));
        }
        ++out.folds;
    }
    if (out.folds == 0) return out;
    const auto folds = static_cast<double>(out.folds);
    std::size_t best = 0;
    for (std::size_t p = 0; p < predictors.size(); ++p) {
        double sum = 0.0;
        for (const double e : errors[p]) sum += e;
        PredictorScore score;
        score.predictor = predictors[p];
        score.cv_rms = sum / folds;
        if (p == 0 || score.cv_rms < out.scores[best].cv_rms) best = p;
        out.scores.push_back(score);
    }
    // The paired standard error of each candidate's excess over the lowest; those within the allowance
    // are averaged with it.
    std::size_t members = 0;
    for (std::size_t p = 0; p < predictors.size(); ++p) {
        PredictorScore& score = out.scores[p];
        if (p != best && out.folds >= 2) {
            const double mean = score.cv_rms - out.scores[best].cv_rms;
            double ss = 0.0;
            for (std::size_t k = 0; k < out.folds; ++k) {
                const double d = errors[p][k] - errors[best][k] - mean;
                ss += d * d;
            }
            score.cv_se = std::sqrt(ss / (folds - 1.0) / folds);
        }
        const bool within = p == best || (out.folds >= 2 && score.cv_rms - out.scores[best].cv_rms <=
                                                                options.average_within_se * score.cv_se);
        score.weight = within ? 1.0 : 0.0;
        if (within) ++members;
    }
    for (PredictorScore& score : out.scores) score.weight /= static_cast<double>(members);
    out.chosen = members > 1 ? Predictor::Average : predictors[best];
    return out;
}

std::string describe(const PredictorChoice& choice) {
    if (choice.folds == 0) return std::string(to_string(choice.chosen)) + " (no fold could be left out)";
    std::string head = to_string(choice.chosen);
    if (choice.chosen == Predictor::Average) {
        head += " of";
        const std::vector<Predictor> members = choice.members();
        for (std::size_t k = 0; k < members.size(); ++k) head += (k ? ", " : " ") + std::string(to_string(members[k]));
    }
    // The lowest first, then the others with their paired standard errors against it.
    std::size_t best = 0;
    for (std::size_t p = 0; p < choice.scores.size(); ++p)
        if (choice.scores[p].cv_rms < choice.scores[best].cv_rms) best = p;
    char buf[96];
    std::string scores;
    for (std::size_t p = 0; p < choice.scores.size(); ++p) {
        const PredictorScore& s = choice.scores[p];
        if (p == best) std::snprintf(buf, sizeof buf, "%s %.3g", to_string(s.predictor), s.cv_rms);
        else std::snprintf(buf, sizeof buf, "%s %.3g ± %.2g", to_string(s.predictor), s.cv_rms, s.cv_se);
        scores = p == best ? buf + (scores.empty() ? "" : ", " + scores) : scores + (scores.empty() ? "" : ", ") + buf;
    }
    return head + " (cv " + scores + "; " + std::to_string(choice.folds) + " folds of " +
           std::to_string(choice.samples) + " samples)";
}

}  // namespace mocapdb::synthesis
