#include "kernel_codec.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "layout.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/core/huge_pages.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store {
namespace {

const char* const kParameters[] = {"exponent", "nugget", "sill", "range"};

double* parameter(kriging::VariogramModel& m, int k) {
    switch (k) {
        case 0: return &m.exponent;
        case 1: return &m.nugget;
        case 2: return &m.sill;
        default: return &m.range;
    }
}

const kriging::FitStatus kFitStatuses[] = {kriging::FitStatus::Ok, kriging::FitStatus::RangeAtBound,
                                           kriging::FitStatus::SillAtBound, kriging::FitStatus::PureNugget,
                                           kriging::FitStatus::Degenerate};

std::string number_text(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

std::string key_text(std::uint64_t key) {
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016" PRIx64, key);
    return buf;
}

// The variogram's constraints; the violated one as text, or "" when they hold.
std::string violation(const synthesis::KernelFit& fit) {
    try {
        fit.variogram.validate();
    } catch (const InvalidArgument& e) {
        return e.what();
    }
    if (!std::isfinite(fit.variogram.exponent)) return "the exponent must be finite";
    if (!(fit.variogram.total_sill() > 0.0)) return "nugget + sill must be > 0";
    return "";
}

// The cross-validated predictor (predictor_choice.hpp) as attributes of the kernel group.
void write_predictor_choice(h5::File& file, const std::string& g, const synthesis::PredictorChoice& c) {
    std::vector<std::string> names;
    std::vector<double> cv, se, weight;
    for (const synthesis::PredictorScore& s : c.scores) {
        names.emplace_back(synthesis::to_string(s.predictor));
        cv.push_back(s.cv_rms);
        se.push_back(s.cv_se);
        weight.push_back(s.weight);
    }
    // A choice whose scores carry no weights blends with the chosen predictor alone.
    if (std::all_of(weight.begin(), weight.end(), [](double w) { return w <= 0.0; }))
        for (std::size_t k = 0; k < weight.size(); ++k) weight[k] = c.scores[k].predictor == c.chosen ? 1.0 : 0.0;
    file.write_string_attribute(g, "predictor", synthesis::to_string(c.chosen));
    file.write_strings_attribute(g, "predictor_candidates", names);
    file.write_doubles_attribute(g, "predictor_cv_rms", cv);
    file.write_doubles_attribute(g, "predictor_cv_se", se);
    file.write_doubles_attribute(g, "predictor_weights", weight);
    file.write_int_attribute(g, "predictor_folds", static_cast<std::int64_t>(c.folds));
    file.write_int_attribute(g, "predictor_samples", static_cast<std::int64_t>(c.samples));
}

synthesis::Predictor predictor_named(const h5::File& file, const std::string& g, const std::string& attribute,
                                     const std::string& name) {
    const auto p = synthesis::parse_predictor(name);
    if (p && (*p != synthesis::Predictor::Average || attribute == "predictor")) return *p;
    throw StoreError(file.name(), g,
                     "attribute '" + attribute + "': expected \"kriging\", \"rbf\", \"trend\"" +
                         (attribute == "predictor" ? " or \"average\"" : "") + ", found \"" + name + "\"");
}

// The stored choice, checked: a known chosen predictor among the candidates, one finite cv >= 0 each.
synthesis::PredictorChoice read_predictor_choice(const h5::File& file, const std::string& g) {
    synthesis::PredictorChoice c;
    c.chosen = predictor_named(file, g, "predictor", file.read_string_attribute(g, "predictor"));
    const std::vector<std::string> names = file.read_strings_attribute(g, "predictor_candidates");
    const std::vector<double> cv = file.read_doubles_attribute(g, "predictor_cv_rms");
    if (names.size() != cv.size() || names.empty())
        throw StoreError(file.name(), g,
                         "attributes 'predictor_candidates' and 'predictor_cv_rms': expected the same non-zero "
                         "length, found " +
                             std::to_string(names.size()) + " and " + std::to_string(cv.size()));
    // The paired standard errors and the blend's weights (written since the average exists; before: the
    // chosen one alone, no errors).
    const bool has_weights = file.has_attribute(g, "predictor_weights");
    if (has_weights != file.has_attribute(g, "predictor_cv_se"))
        throw StoreError(file.name(), g, "attributes 'predictor_cv_se' and 'predictor_weights': expected both or none");
    std::vector<double> se(names.size(), 0.0), weight(names.size(), 0.0);
    if (has_weights) {
        se = file.read_doubles_attribute(g, "predictor_cv_se");
        weight = file.read_doubles_attribute(g, "predictor_weights");
        if (se.size() != names.size() || weight.size() != names.size())
            throw StoreError(file.name(), g,
                             "attributes 'predictor_cv_se' and 'predictor_weights': expected " +
                                 std::to_string(names.size()) + " values each (one per candidate), found " +
                                 std::to_string(se.size()) + " and " + std::to_string(weight.size()));
    }
    bool chosen_listed = false;
    std::size_t members = 0;
    double weight_sum = 0.0;
    for (std::size_t k = 0; k < names.size(); ++k) {
        const synthesis::Predictor p = predictor_named(file, g, "predictor_candidates", names[k]);
        if (!(cv[k] >= 0.0) || !std::isfinite(cv[k]))
            throw StoreError(file.name(), g,
                             "attribute 'predictor_cv_rms': expected finite values >= 0, found " + number_text(cv[k]));
        if (!(se[k] >= 0.0) || !std::isfinite(se[k]))
            throw StoreError(file.name(), g,
                             "attribute 'predictor_cv_se': expected finite values >= 0, found " + number_text(se[k]));
        if (!(weight[k] >= 0.0 && weight[k] <= 1.0))
            throw StoreError(
                file.name(), g,
                "attribute 'predictor_weights': expected values in [0, 1], found " + number_text(weight[k]));
        if (!has_weights && p == c.chosen) weight[k] = 1.0;
        chosen_listed = chosen_listed || p == c.chosen;
        members += weight[k] > 0.0 ? 1 : 0;
        weight_sum += weight[k];
        synthesis::PredictorScore score;
        score.predictor = p;
        score.cv_rms = cv[k];
        score.cv_se = se[k];
        score.weight = weight[k];
        c.scores.push_back(score);
    }
    const bool average = c.chosen == synthesis::Predictor::Average;
    if (!average && !chosen_listed)
        throw StoreError(file.name(), g,
                         "attribute 'predictor': \"" + std::string(synthesis::to_string(c.chosen)) +
                             "\" is not among 'predictor_candidates'");
    if (average && members < 2)
        throw StoreError(file.name(), g,
                         "attribute 'predictor' is \"average\": expected 'predictor_weights' with at least 2 "
                         "positive values, found " +
                             std::to_string(members));
    if (has_weights && (std::abs(weight_sum - 1.0) > 1e-9 || (!average && members != 1)))
        throw StoreError(file.name(), g,
                         "attribute 'predictor_weights': expected weights summing to 1, positive for the chosen "
                         "predictor (or the averaged ones) only, found a sum of " +
                             number_text(weight_sum) + " over " + std::to_string(members) + " positive");
    const std::int64_t folds = file.read_int_attribute(g, "predictor_folds");
    const std::int64_t samples = file.read_int_attribute(g, "predictor_samples");
    if (folds < 1 || samples < folds)
        throw StoreError(
            file.name(), g,
            "attributes 'predictor_folds' and 'predictor_samples': expected 1 <= folds <= samples, found " +
                std::to_string(folds) + " and " + std::to_string(samples));
    c.folds = static_cast<std::size_t>(folds);
    c.samples = static_cast<std::size_t>(samples);
    return c;
}

// The calibrated warning threshold (edge_warning.hpp) as attributes of the kernel group.
const char* const kEdgeShares[] = {"edge_detection", "edge_false_alarms"};

void write_edge_warning(h5::File& file, const std::string& g, const synthesis::EdgeWarning& w) {
    file.write_double_attribute(g, "edge_variance_ratio", w.variance_ratio);
    file.write_double_attribute(g, "edge_beyond_sd", w.beyond_sd);
    file.write_double_attribute(g, "edge_detection", w.detection);
    file.write_double_attribute(g, "edge_false_alarms", w.false_alarms);
    file.write_double_attribute(g, "edge_tolerance_share", w.tolerance_share);
    file.write_int_attribute(g, "edge_probes", static_cast<std::int64_t>(w.probes));
    file.write_int_attribute(g, "edge_misses", static_cast<std::int64_t>(w.misses));
    if (w.votes == 0) return;
    // The vote rule: its counts, and the calibration's requests (C order: a row each) and misses.
    file.write_int_attribute(g, "edge_neighbours", static_cast<std::int64_t>(w.neighbours));
    file.write_int_attribute(g, "edge_votes", static_cast<std::int64_t>(w.votes));
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = w.probe_requests;
    file.write_array(g + "/edge_probe_requests", rows.data(),
                     {static_cast<std::uint64_t>(rows.rows()), static_cast<std::uint64_t>(rows.cols())},
                     {"probe", "parameter"}, "parameter_unit");
    file.write_ints_attribute(g + "/edge_probe_requests", "missed",
                              std::vector<std::int64_t>(w.probe_missed.begin(), w.probe_missed.end()));
}

// The vote rule's counts and requests, checked: 1 <= votes <= neighbours, finite requests, a 0/1 miss
// flag per request.
void read_edge_votes(const h5::File& file, const std::string& g, synthesis::EdgeWarning& w) {
    const std::int64_t neighbours = file.read_int_attribute(g, "edge_neighbours");
    const std::int64_t votes = file.read_int_attribute(g, "edge_votes");
    if (neighbours < 1 || votes < 1 || votes > neighbours)
        throw StoreError(file.name(), g,
                         "attributes 'edge_neighbours' and 'edge_votes': expected 1 <= votes <= neighbours, found " +
                             std::to_string(votes) + " and " + std::to_string(neighbours));
    w.neighbours = static_cast<std::size_t>(neighbours);
    w.votes = static_cast<std::size_t>(votes);
    const std::string path = g + "/edge_probe_requests";
    const h5::Array<double> a = file.read_array<double>(path, 2);
    w.probe_requests.resize(static_cast<Eigen::Index>(a.shape[0]), static_cast<Eigen::Index>(a.shape[1]));
    for (Eigen::Index i = 0; i < w.probe_requests.rows(); ++i)
        for (Eigen::Index p = 0; p < w.probe_requests.cols(); ++p)
            w.probe_requests(i, p) = a.data[static_cast<std::size_t>(i * w.probe_requests.cols() + p)];
    if (!w.probe_requests.allFinite())
        throw StoreError(file.name(), path, "expected finite requests, found a NaN or infinity");
    const std::vector<std::int64_t> missed = file.read_ints_attribute(path, "missed");
    if (missed.size() != a.shape[0] || a.shape[0] != w.probes ||
        std::any_of(missed.begin(), missed.end(), [](std::int64_t m) { return m != 0 && m != 1; }))
        throw StoreError(file.name(), path,
                         "attribute 'missed': expected a 0 or 1 per request, one request per probe (" +
                             std::to_string(w.probes) + "), found " + std::to_string(missed.size()) + " flags for " +
                             std::to_string(a.shape[0]) + " requests");
    w.probe_missed.assign(missed.begin(), missed.end());
}

// The stored calibration, checked: a finite ratio and distance >= 0, shares in [0, 1], a positive tolerance, 0 <= misses <= probes, probes >= 1.
synthesis::EdgeWarning read_edge_warning(const h5::File& file, const std::string& g) {
    synthesis::EdgeWarning w;
    w.variance_ratio = file.read_double_attribute(g, "edge_variance_ratio");
    if (!(w.variance_ratio >= 0.0) || !std::isfinite(w.variance_ratio))
        throw StoreError(
            file.name(), g,
            "attribute 'edge_variance_ratio': expected a finite number >= 0, found " + number_text(w.variance_ratio));
    w.beyond_sd = file.read_double_attribute(g, "edge_beyond_sd");
    if (!(w.beyond_sd >= 0.0) || !std::isfinite(w.beyond_sd))
        throw StoreError(
            file.name(), g,
            "attribute 'edge_beyond_sd': expected a finite number >= 0, found " + number_text(w.beyond_sd));
    double* const shares[] = {&w.detection, &w.false_alarms};
    for (int k = 0; k < 2; ++k) {
        *shares[k] = file.read_double_attribute(g, kEdgeShares[k]);
        if (!(*shares[k] >= 0.0 && *shares[k] <= 1.0))
            throw StoreError(file.name(), g,
                             std::string("attribute '") + kEdgeShares[k] + "': expected a number in [0, 1], found " +
                                 number_text(*shares[k]));
    }
    w.tolerance_share = file.read_double_attribute(g, "edge_tolerance_share");
    if (!(w.tolerance_share > 0.0) || !std::isfinite(w.tolerance_share))
        throw StoreError(
            file.name(), g,
            "attribute 'edge_tolerance_share': expected a finite number > 0, found " + number_text(w.tolerance_share));
    const std::int64_t probes = file.read_int_attribute(g, "edge_probes");
    const std::int64_t misses = file.read_int_attribute(g, "edge_misses");
    if (probes < 1 || misses < 0 || misses > probes)
        throw StoreError(file.name(), g,
                         "attributes 'edge_probes' and 'edge_misses': expected 0 <= misses <= probes, probes >= 1, "
                         "found " +
                             std::to_string(misses) + " and " + std::to_string(probes));
    w.probes = static_cast<std::size_t>(probes);
    w.misses = static_cast<std::size_t>(misses);
    if (file.has_attribute(g, "edge_votes")) read_edge_votes(file, g, w);
    return w;
}

}  // namespace

void check_kernel_fit(const synthesis::KernelFit& fit, const std::string& who) {
    if (fit.key == 0) throw InvalidArgument(who + ": the kernel fit has no key (0)");
    const std::string v = violation(fit);
    if (!v.empty()) throw InvalidArgument(who + ": " + v);
    if (fit.assessed_status && !(fit.residual_variance >= 0.0 && std::isfinite(fit.residual_variance)))
        throw InvalidArgument(who + ": the residual variance must be finite and >= 0");
    if (fit.system && (fit.system->inverse.rows() != fit.system->inverse.cols() || fit.system->inverse.size() == 0 ||
                       !fit.system->inverse.allFinite()))
        throw InvalidArgument(who + ": the factorized system must be a square, non-empty, finite matrix");
    if (const auto& w = fit.edge_warning;
        w && !(w->variance_ratio >= 0.0 && std::isfinite(w->variance_ratio) && w->beyond_sd >= 0.0 &&
               std::isfinite(w->beyond_sd) && w->detection >= 0.0 && w->detection <= 1.0 && w->false_alarms >= 0.0 &&
               w->false_alarms <= 1.0 && w->tolerance_share > 0.0 && std::isfinite(w->tolerance_share) &&
               w->probes >= 1 && w->misses <= w->probes))
        throw InvalidArgument(
            who +
            ": the edge warning needs a finite variance ratio and distance >= 0, shares in [0, 1], a positive tolerance "
            "and 0 <= misses <= probes >= 1");
    if (const auto& w = fit.edge_warning;
        w && w->votes > 0 &&
        !(w->votes <= w->neighbours && w->probe_requests.rows() == static_cast<Eigen::Index>(w->probes) &&
          w->probe_missed.size() == w->probes && w->probe_requests.allFinite()))
        throw InvalidArgument(who +
                              ": the edge warning's vote rule needs 1 <= votes <= neighbours and a finite request and "
                              "a miss flag per probe");
}

void write_kernel_fit(h5::File& file, const std::string& set, const synthesis::KernelFit& fit) {
    const std::string g = kernel_path(set);
    file.create_group(g, "kernel_fit");
    file.write_string_attribute(g, "key", key_text(fit.key));
    file.write_string_attribute(g, "family", kriging::to_string(fit.variogram.family));
    kriging::VariogramModel m = fit.variogram;
    for (int k = 0; k < 4; ++k) file.write_double_attribute(g, kParameters[k], *parameter(m, k));
    if (fit.assessed_status) {
        file.write_string_attribute(g, "fit_status", kriging::to_string(*fit.assessed_status));
        file.write_double_attribute(g, "residual_variance", fit.residual_variance);
    }
    if (fit.predictor) write_predictor_choice(file, g, *fit.predictor);
    if (fit.edge_warning) write_edge_warning(file, g, *fit.edge_warning);
    if (fit.system) {
        // The factorized system in C order: the column-major buffer itself when the matrix is exactly
        // symmetric (as Kriging::covariance_inverse returns it), else transposed on the way. Fletcher32
        // only: deflate does not shrink full-precision doubles, and inflating them cost most of the read.
        const kriging::CovarianceInverse& c = *fit.system;
        const auto points = static_cast<std::uint64_t>(c.inverse.rows());
        const std::string path = g + "/covariance_inverse";
        if (c.inverse == c.inverse.transpose()) {
            file.write_array_checksum_only(path, c.inverse.data(), {points, points}, {"point", "point"}, "1/cm^2");
        } else {
            const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = c.inverse;
            file.write_array_checksum_only(path, rows.data(), {points, points}, {"point", "point"}, "1/cm^2");
        }
        file.write_string_attribute(g + "/covariance_inverse", "factorization", kriging::to_string(c.factorization));
        file.write_double_attribute(g + "/covariance_inverse", "jitter", c.jitter);
        file.write_double_attribute(g + "/covariance_inverse", "rcond", c.rcond);
    }
}

namespace {

// The stored factorized system (write_kernel_fit), checked: square, finite, a known factorization.
std::shared_ptr<const kriging::CovarianceInverse> read_system(const h5::File& file, const std::string& g) {
    const std::string path = g + "/covariance_inverse";
    auto c = std::make_shared<kriging::CovarianceInverse>();
    // C order read into the column-major matrix gives its transpose: the same matrix when it is exactly
    // symmetric (as written since the system is stored unfiltered), else transposed back in place.
    Eigen::MatrixXd& a = c->inverse;
    file.read_array_into<double>(path, 2, [&](const h5::Shape& shape) {
        if (shape[0] != shape[1] || shape[0] == 0)
            throw StoreError(file.name(), path,
                             "expected a square, non-empty (point, point) matrix, found " + std::to_string(shape[0]) +
                                 "x" + std::to_string(shape[1]));
        a.resize(static_cast<Eigen::Index>(shape[0]), static_cast<Eigen::Index>(shape[1]));
        advise_huge_pages(a);  // before HDF5 writes it: 2 MB pages instead of 18 000 faults at M = 3 043
        return a.data();
    });
    if (!a.allFinite()) throw StoreError(file.name(), path, "expected finite values, found a NaN or infinity");
    constexpr Eigen::Index tile = 64;  // square tiles: a transposed pass over the whole matrix misses the cache
    const Eigen::Index m = a.rows();
    for (Eigen::Index j0 = 0; j0 < m; j0 += tile)
        for (Eigen::Index i0 = j0; i0 < m; i0 += tile)
            for (Eigen::Index j = j0; j < std::min(j0 + tile, m); ++j)
                for (Eigen::Index i = std::max(i0, j + 1); i < std::min(i0 + tile, m); ++i)
                    if (a(i, j) != a(j, i)) std::swap(a(i, j), a(j, i));
    const std::string how = file.read_string_attribute(path, "factorization");
    bool known = false;
    for (const auto f : {kriging::FactorizationStatus::Ok, kriging::FactorizationStatus::Jittered,
                         kriging::FactorizationStatus::Regularized})
        if (how == kriging::to_string(f)) {
            c->factorization = f;
            known = true;
        }
    if (!known)
        throw StoreError(
            file.name(), path,
            "attribute 'factorization': expected \"ok\", \"jittered\" or \"regularized\", found \"" + how + "\"");
    c->jitter = file.read_double_attribute(path, "jitter");
    c->rcond = file.read_double_attribute(path, "rcond");
    return c;
}

}  // namespace

synthesis::KernelFit read_kernel_fit(const h5::File& file, const std::string& set) {
    const std::string g = kernel_path(set);
    synthesis::KernelFit fit;
    const std::string key = file.read_string_attribute(g, "key");
    bool hex = key.size() == 16;
    for (const char c : key) hex = hex && ((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'));
    if (!hex)
        throw StoreError(file.name(), g,
                         "attribute 'key': expected 16 lowercase hexadecimal digits, found \"" + key + "\"");
    fit.key = std::strtoull(key.c_str(), nullptr, 16);
    if (fit.key == 0)
        throw StoreError(file.name(), g, "attribute 'key': expected a non-zero digest, found \"" + key + "\"");
    const std::string family = file.read_string_attribute(g, "family");
    if (family == kriging::to_string(kriging::VariogramFamily::Spherical))
        fit.variogram.family = kriging::VariogramFamily::Spherical;
    else if (family == kriging::to_string(kriging::VariogramFamily::Stable))
        fit.variogram.family = kriging::VariogramFamily::Stable;
    else
        throw StoreError(file.name(), g,
                         "attribute 'family': expected \"sph\" or \"stable\", found \"" + family + "\"");
    for (int k = 0; k < 4; ++k) *parameter(fit.variogram, k) = file.read_double_attribute(g, kParameters[k]);
    const std::string v = violation(fit);
    if (!v.empty()) throw StoreError(file.name(), g, v);
    // The model's fit status, optional (kernels written before it was stored have neither attribute).
    const bool has_status = file.has_attribute(g, "fit_status");
    if (has_status != file.has_attribute(g, "residual_variance"))
        throw StoreError(file.name(), g,
                         std::string("attribute '") + (has_status ? "residual_variance" : "fit_status") +
                             "': missing (fit_status and residual_variance go together)");
    if (has_status) {
        const std::string status = file.read_string_attribute(g, "fit_status");
        for (const kriging::FitStatus s : kFitStatuses)
            if (status == kriging::to_string(s)) fit.assessed_status = s;
        if (!fit.assessed_status) {
            std::string allowed;
            for (const kriging::FitStatus s : kFitStatuses)
                allowed += (allowed.empty() ? "\"" : ", \"") + std::string(kriging::to_string(s)) + "\"";
            throw StoreError(file.name(), g,
                             "attribute 'fit_status': expected one of " + allowed + ", found \"" + status + "\"");
        }
        fit.residual_variance = file.read_double_attribute(g, "residual_variance");
        if (!(fit.residual_variance >= 0.0) || !std::isfinite(fit.residual_variance))
            throw StoreError(file.name(), g,
                             "attribute 'residual_variance': expected a finite number >= 0, found " +
                                 number_text(fit.residual_variance));
    }
    if (file.has_attribute(g, "predictor")) fit.predictor = read_predictor_choice(file, g);
    if (file.has_attribute(g, "edge_variance_ratio")) fit.edge_warning = read_edge_warning(file, g);
    if (file.exists(g + "/covariance_inverse")) fit.system = read_system(file, g);
    return fit;
}

}  // namespace mocapdb::store
