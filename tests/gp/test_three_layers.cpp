// Three-layer MOHGP (trend → group → child): the structured and low-rank likelihoods against the dense
// oracle and finite differences, the reductions to two layers, posteriors, sampling, argument checks.
#include <catch2/catch.hpp>

#include "gp_fixtures.hpp"
#include "mocapdb/core/error.hpp"

using namespace mocapdb;
using namespace mocapdb::gp;
using namespace mocapdb::gp::test;

namespace {

HgpData grouped_data(Eigen::Index d, Eigen::Index t, const std::vector<std::size_t>& groups, std::uint64_t seed) {
    HgpData data = make_data(d, t, groups.size(), seed);
    data.groups = groups;
    return data;
}

/// The same likelihood (value and gradient, parameters in the same order) on every path.
void check_same_model(const HgpModel& a, const HgpData& da, const HgpModel& b, const HgpData& db) {
    for (LikelihoodPath path : {LikelihoodPath::Dense, LikelihoodPath::Structured, LikelihoodPath::LowRank}) {
        INFO("path " << static_cast<int>(path));
        check_same_likelihood(log_likelihood(a, da, true, path), log_likelihood(b, db, true, path), 1e-10);
    }
}

std::string describe(const std::vector<std::size_t>& groups) {
    std::string s;
    for (std::size_t g : groups) s += std::to_string(g);
    return s;
}

}  // namespace

TEST_CASE("three layers: structured and low-rank likelihoods and gradients equal the dense oracle", "[gp][likelihood][layers]") {
    struct Case {
        Eigen::Index d, t;
        std::vector<std::size_t> groups;
        std::size_t terms;
        Eigen::Index rank;
    };
    // Balanced groups (one size), unequal sizes (the coupled size classes), one child per group and one
    // group; n = D·T = 150 crosses the blocked inverse's block boundary.
    const Case cases[] = {{2, 6, {0, 0, 1, 1}, 2, 1},     {3, 8, {0, 1, 2, 0, 1, 2}, 1, 2}, {2, 7, {0, 1, 2}, 2, 1},
                          {2, 6, {0, 0, 0}, 1, 1},        {3, 50, {1, 0, 1, 0}, 1, 1},      {2, 6, {0, 1, 1}, 2, 1},
                          {2, 5, {0, 1, 1, 2, 2, 2}, 1, 2}, {3, 50, {0, 0, 1}, 1, 1}};
    for (const Case& c : cases) {
        const HgpModel model = make_grouped_model(c.d, c.terms, c.rank);
        const HgpData data = grouped_data(c.d, c.t, c.groups, 41 + c.groups.size());
        const LikelihoodValue dense = log_likelihood(model, data, true, LikelihoodPath::Dense);
        REQUIRE(dense.ok());
        for (int threads : {1, 2})
            for (LikelihoodPath path : {LikelihoodPath::Structured, LikelihoodPath::LowRank}) {
                INFO("groups " << describe(c.groups) << " D=" << c.d << " T=" << c.t << " threads=" << threads << " path "
                               << static_cast<int>(path) << " against dense");
                check_same_likelihood(log_likelihood(model, data, true, path, threads), dense);
            }
    }
}

TEST_CASE("three layers: analytic gradients match finite differences", "[gp][likelihood][layers]") {
    const HgpModel model = make_grouped_model(2, 2, 1);
    // Dense with a partial child; structured and low rank with unequal groups (coupled), low rank with
    // equal groups.
    HgpData partial = grouped_data(2, 5, {0, 0, 1}, 3);
    partial.observed = {{}, {true, false, true, true, false}, {}};
    const HgpData unequal = grouped_data(2, 5, {0, 1, 1, 2, 2, 2}, 4);
    const HgpData equal = grouped_data(2, 5, {0, 1, 0, 1}, 5);
    const std::pair<const HgpData*, LikelihoodPath> runs[] = {
        {&partial, LikelihoodPath::Dense}, {&unequal, LikelihoodPath::Structured}, {&unequal, LikelihoodPath::LowRank},
        {&equal, LikelihoodPath::LowRank}};
    for (const auto& [data, path] : runs) {
        const LikelihoodValue v = log_likelihood(model, *data, true, path);
        REQUIRE(v.ok());
        const VecX fd = finite_difference_gradient(model, *data, path);
        const double diff = max_relative_difference(v.gradient, fd);
        INFO("path " << static_cast<int>(path) << ": analytic vs finite differences " << diff << " over " << fd.size()
                     << " parameters");
        CHECK(diff < 1e-6);
    }
}

TEST_CASE("three layers with one child per group equal two layers with K_f + K_h as the child covariance", "[gp][layers]") {
    const Eigen::Index d = 2, t = 7;
    const HgpModel three = make_grouped_model(d, 2, 1);
    // Two layers whose child LMC is the three-layer child terms followed by the group terms: the same
    // covariance, and the same parameter order (child, group, parent, noise).
    HgpModel two = three;
    two.grouped = false;
    two.group.terms.clear();
    for (const auto& term : three.group.terms) two.child.terms.push_back(term);
    HgpData data = grouped_data(d, t, {2, 0, 1}, 9);
    HgpData plain = data;
    plain.groups.clear();
    check_same_model(three, data, two, plain);
    // Posteriors: the trend, and a partially observed child (its group function is then its own f − ε).
    const VecX ts = VecX::LinSpaced(5, -0.3, 2.4);
    CHECK((predict_parent(three, data, ts).mean - predict_parent(two, plain, ts).mean).cwiseAbs().maxCoeff() < 1e-10);
    data.observed = plain.observed = {{}, {true, false, false, true, false, false, true}, {}};
    const GaussianPrediction a = predict_child(three, data, 1, ts), b = predict_child(two, plain, 1, ts);
    CHECK((a.mean - b.mean).cwiseAbs().maxCoeff() < 1e-10);
    CHECK((a.variance - b.variance).cwiseAbs().maxCoeff() < 1e-10);
}

TEST_CASE("three layers with one group equal two layers with K_h + K_g as the parent covariance", "[gp][layers]") {
    const Eigen::Index d = 2, t = 6;
    const HgpModel three = make_grouped_model(d, 1, 2);
    HgpModel two = three;
    two.grouped = false;
    two.parent.terms = three.group.terms;  // order: child, group, parent, noise in both
    for (const auto& term : three.parent.terms) two.parent.terms.push_back(term);
    const HgpData data = grouped_data(d, t, {0, 0, 0, 0}, 12);
    HgpData plain = data;
    plain.groups.clear();
    check_same_model(three, data, two, plain);
    // The group function of the only group is the two-layer parent.
    const VecX ts = VecX::LinSpaced(4, 0.1, 2.2);
    CHECK((predict_group(three, data, 0, ts).mean - predict_parent(two, plain, ts).mean).cwiseAbs().maxCoeff() < 1e-10);
}

TEST_CASE("three-layer posteriors: structured equals dense", "[gp][layers][posterior]") {
    const Eigen::Index d = 2, t = 9;
    const HgpModel model = make_grouped_model(d, 2, 1);
    const VecX ts = VecX::LinSpaced(6, -0.2, 2.3);
    for (const std::vector<std::size_t>& groups : {std::vector<std::size_t>{0, 0, 1, 1}, std::vector<std::size_t>{0, 1, 1, 2, 2, 2}}) {
        HgpData data = grouped_data(d, t, groups, 21);
        INFO("groups " << describe(groups));
        const GaussianPrediction ps = predict_parent(model, data, ts), pd = predict_parent_dense(model, data, ts);
        CHECK((ps.mean - pd.mean).cwiseAbs().maxCoeff() < 1e-9);
        CHECK((ps.variance - pd.variance).cwiseAbs().maxCoeff() < 1e-9);
        for (std::size_t s = 0; s < data.group_count(); ++s) {
            const GaussianPrediction gs = predict_group(model, data, s, ts), gd = predict_group_dense(model, data, s, ts);
            CHECK((gs.mean - gd.mean).cwiseAbs().maxCoeff() < 1e-9);
            CHECK((gs.variance - gd.variance).cwiseAbs().maxCoeff() < 1e-9);
        }
        // A partially observed child in a group with siblings, and one alone in its group.
        for (std::size_t child : {std::size_t{1}, std::size_t{0}}) {
            data.observed.assign(groups.size(), {});
            data.observed[child] = {true, false, false, true, false, true, false, false, true};
            const GaussianPrediction cs = predict_child(model, data, child, ts), cd = predict_child_dense(model, data, child, ts);
            INFO("child " << child);
            CHECK((cs.mean - cd.mean).cwiseAbs().maxCoeff() < 1e-9);
            CHECK((cs.variance - cd.variance).cwiseAbs().maxCoeff() < 1e-9);
        }
        // With a partial child the group posterior falls back to dense and still agrees with it.
        CHECK((predict_group(model, data, 0, ts).mean - predict_group_dense(model, data, 0, ts).mean).cwiseAbs().maxCoeff() < 1e-12);
    }
}

TEST_CASE("three-layer samples: a new child of a new group varies by K_h + K_f around the trend", "[gp][layers][synthesis]") {
    const Eigen::Index d = 1, t = 6;
    const HgpModel model = make_grouped_model(d, 1, 1);
    const HgpData data = grouped_data(d, t, {0, 0, 1, 1}, 31);
    const VecX ts = VecX::LinSpaced(3, 0.2, 1.8);
    const std::size_t n = 20000;
    const auto samples = sample_children(model, data, ts, n);
    const MatX trend = synthesis_trend(model, data, ts);
    MatX cov = MatX::Zero(3, 3);
    VecX mean = VecX::Zero(3);
    for (const MatX& s : samples) mean += s.row(0).transpose();
    mean /= static_cast<double>(n);
    for (const MatX& s : samples) {
        const VecX dev = s.row(0).transpose() - trend.row(0).transpose();
        cov += dev * dev.transpose();
    }
    cov /= static_cast<double>(n);
    const MatX expected = lmc_covariance(model.group, ts, ts) + lmc_covariance(model.child, ts, ts);
    INFO("empirical\n" << cov << "\nexpected\n" << expected);
    CHECK((mean - trend.row(0).transpose()).cwiseAbs().maxCoeff() < 5.0 * std::sqrt(expected.diagonal().maxCoeff() / static_cast<double>(n)));
    CHECK((cov - expected).cwiseAbs().maxCoeff() < 0.05 * expected.diagonal().maxCoeff());
    // Deterministic for a seed.
    CHECK(sample_children(model, data, ts, 2)[1] == samples[1]);
    // New children of existing group 1: around its function's posterior mean, varying by K_f.
    SampleOptions in_group;
    in_group.group = 1;
    const auto kids = sample_children(model, data, ts, n, in_group);
    const VecX group_mean = predict_group(model, data, 1, ts).mean.row(0).transpose();
    MatX kcov = MatX::Zero(3, 3);
    for (const MatX& s : kids) {
        const VecX dev = s.row(0).transpose() - group_mean;
        kcov += dev * dev.transpose();
    }
    kcov /= static_cast<double>(n);
    const MatX kf = lmc_covariance(model.child, ts, ts);
    INFO("in group 1: empirical\n" << kcov << "\nexpected K_f\n" << kf);
    CHECK((kcov - kf).cwiseAbs().maxCoeff() < 0.05 * kf.diagonal().maxCoeff());
    in_group.group = 2;
    CHECK_THROWS_AS(sample_children(model, data, ts, 1, in_group), InvalidArgument);
    in_group.group = 0;
    CHECK_THROWS_AS(sample_children(make_model(d, true, 1, 1), data, ts, 1, in_group), InvalidArgument);
}

TEST_CASE("three-layer arguments are checked", "[gp][layers]") {
    const HgpModel model = make_grouped_model(2, 1, 1);
    HgpData data = make_data(2, 5, 3);
    CHECK_THROWS_AS(log_likelihood(model, data, false), InvalidArgument);  // no groups
    data.groups = {0, 2, 2};                                                 // group 1 empty
    CHECK_THROWS_AS(log_likelihood(model, data, false), InvalidArgument);
    data.groups = {0, 1};                                                    // one index short
    CHECK_THROWS_AS(log_likelihood(model, data, false), InvalidArgument);
    data.groups = {0, 1, 1};
    CHECK(log_likelihood(model, data, false).ok());
    HgpModel flat = model;
    flat.hierarchical = false;  // grouped without a trend
    CHECK_THROWS_AS(log_likelihood(flat, data, false), InvalidArgument);
    HgpModel empty = model;
    empty.group.terms.clear();
    CHECK_THROWS_AS(log_likelihood(empty, data, false), InvalidArgument);
    CHECK_THROWS_AS(predict_group(model, data, 2, data.times), InvalidArgument);
    CHECK_THROWS_AS(predict_group(make_model(2, true), data, 0, data.times), InvalidArgument);
    // Parameter names follow the order child, group, parent, noise.
    const auto names = model.parameter_names();
    REQUIRE(names.size() == model.parameter_count());
    CHECK(names[model.child.parameter_count()].rfind("group.q0.", 0) == 0);
    CHECK(names[model.child.parameter_count() + model.group.parameter_count()].rfind("parent.q0.", 0) == 0);
}
