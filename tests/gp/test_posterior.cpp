// Posterior of the parent trend and of a (partially observed) child: structured vs dense oracle;
// sampling new children; MOA baseline behaviour.
#include <catch2/catch.hpp>

#include "gp_fixtures.hpp"
#include "mocapdb/core/error.hpp"

using namespace mocapdb;
using namespace mocapdb::gp;
using namespace mocapdb::gp::test;

TEST_CASE("parent and child posteriors: structured equals dense", "[gp][posterior]") {
    const Eigen::Index d = 3, t = 12;
    const HgpModel model = make_model(d, true, 2, 1);
    HgpData data = make_data(d, t, 4);
    const VecX ts = VecX::LinSpaced(7, -0.2, 2.3);  // new times, some outside the data

    const GaussianPrediction ps = predict_parent(model, data, ts);
    const GaussianPrediction pd = predict_parent_dense(model, data, ts);
    INFO("parent mean diff " << (ps.mean - pd.mean).cwiseAbs().maxCoeff());
    CHECK((ps.mean - pd.mean).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((ps.variance - pd.variance).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((ps.variance.array() > 0).all());

    // Test child 3 observed at 4 of 12 frames; its siblings complete.
    data.observed = {{}, {}, {}, {false, true, false, false, true, false, false, false, true, false, true, false}};
    for (std::size_t child : {std::size_t{3}, std::size_t{0}}) {
        if (child == 0) data.observed = {{}, {}, {}, {}};
        const GaussianPrediction cs = predict_child(model, data, child, ts);
        const GaussianPrediction cd = predict_child_dense(model, data, child, ts);
        const double dm = (cs.mean - cd.mean).cwiseAbs().maxCoeff(), dv = (cs.variance - cd.variance).cwiseAbs().maxCoeff();
        INFO("child " << child << ": mean diff " << dm << ", variance diff " << dv);
        CHECK(dm < 1e-9);
        CHECK(dv < 1e-9);
    }
    // The parent posterior with a partial child falls back to dense and still agrees with it.
    data.observed = {{}, {}, {true, false, true, true, true, true, false, true, true, true, true, true}, {}};
    const GaussianPrediction pp = predict_parent(model, data, ts);
    CHECK((pp.mean - predict_parent_dense(model, data, ts).mean).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("observed frames of a child are reproduced, unobserved ones lean on the siblings", "[gp][posterior]") {
    const Eigen::Index d = 2, t = 15;
    HgpModel model = make_model(d, true, 1, 1);
    model.log_noise.setConstant(std::log(1e-6));
    HgpData data = make_data(d, t, 3);
    // Child 2 only sees frames 0, 7, 14.
    std::vector<bool> mask(t, false);
    mask[0] = mask[7] = mask[14] = true;
    data.observed = {{}, {}, mask};
    const GaussianPrediction p = predict_child(model, data, 2, data.times);
    for (Eigen::Index f : {0, 7, 14}) {
        CHECK((p.mean.col(f) - data.children[2].col(f)).cwiseAbs().maxCoeff() < 1e-3);
        CHECK(p.variance.col(f).maxCoeff() < 1e-4);
    }
    CHECK(p.variance.col(3).minCoeff() > p.variance.col(7).maxCoeff());
    // MOA: without observations of its own, a child's posterior is the prior (siblings independent).
    HgpModel moa = make_model(d, false, 1, 1);
    data.observed = {{}, {}, std::vector<bool>(t, false)};
    const GaussianPrediction m = predict_child(moa, data, 2, data.times);
    CHECK(m.mean.cwiseAbs().maxCoeff() == 0.0);
    CHECK_THROWS_AS(predict_parent(moa, data, data.times), InvalidArgument);
    CHECK_THROWS_AS(predict_child(model, data, 7, data.times), InvalidArgument);
}

TEST_CASE("sampling new children: deterministic, around the trend, with the child covariance", "[gp][synthesis]") {
    const Eigen::Index d = 2, t = 10;
    const HgpModel model = make_model(d, true, 1, 1);
    const HgpData data = make_data(d, t, 3);
    const VecX ts = VecX::LinSpaced(8, 0.0, 2.0);
    SampleOptions o;
    o.seed = 42;
    const auto a = sample_children(model, data, ts, 300, o);
    const auto b = sample_children(model, data, ts, 300, o);
    REQUIRE(a.size() == 300);
    CHECK(a[0].rows() == d);
    CHECK(a[0].cols() == ts.size());
    CHECK((a[17] - b[17]).cwiseAbs().maxCoeff() == 0.0);
    o.seed = 43;
    CHECK((sample_children(model, data, ts, 1, o)[0] - a[0]).cwiseAbs().maxCoeff() > 0.0);
    // Sample mean → trend (the parent's posterior mean), sample variance → diag K_f.
    MatX mean = MatX::Zero(d, ts.size()), sq = MatX::Zero(d, ts.size());
    for (const MatX& s : a) {
        mean += s;
        sq += s.cwiseAbs2();
    }
    mean /= 300.0;
    const MatX var = sq / 300.0 - mean.cwiseAbs2();
    const MatX trend = synthesis_trend(model, data, ts);
    CHECK((trend - predict_parent(model, data, ts).mean).cwiseAbs().maxCoeff() == 0.0);
    const MatX kf = lmc_covariance(model.child, ts, ts);
    for (Eigen::Index i = 0; i < d; ++i)
        for (Eigen::Index f = 0; f < ts.size(); ++f) {
            const double sd = std::sqrt(kf(i * ts.size() + f, i * ts.size() + f));
            CHECK(std::abs(mean(i, f) - trend(i, f)) < 4.0 * sd / std::sqrt(300.0));
            CHECK(var(i, f) == Approx(sd * sd).epsilon(0.3));
        }
    // MOA trend: close to the children's mean for a model whose noise is small.
    HgpModel moa = make_model(d, false, 1, 1);
    const MatX mt = synthesis_trend(moa, data, data.times);
    MatX ybar = (data.children[0] + data.children[1] + data.children[2]) / 3.0;
    CHECK((mt - ybar).cwiseAbs().maxCoeff() < 0.5);
    CHECK(sample_children(moa, data, ts, 2, o).size() == 2);
}

TEST_CASE("predictions under several masks of one child equal one prediction per mask", "[gp][posterior]") {
    const Eigen::Index d = 2, t = 10;
    std::vector<std::vector<bool>> masks = {std::vector<bool>(t, false), std::vector<bool>(t, false), std::vector<bool>(t, true)};
    masks[0][2] = masks[0][7] = true;
    for (Eigen::Index f = 0; f < t; f += 2) masks[1][static_cast<std::size_t>(f)] = true;
    for (int layers : {1, 2, 3}) {
        const HgpModel model = layers == 3 ? make_grouped_model(d, 1, 1) : make_model(d, layers == 2, 2, 1);
        HgpData data = make_data(d, t, 4);
        if (layers == 3) data.groups = {0, 1, 1, 0};
        const auto many = predict_child_masks(model, data, 1, masks);
        REQUIRE(many.size() == masks.size());
        for (std::size_t i = 0; i < masks.size(); ++i) {
            HgpData one = data;
            one.observed = {{}, masks[i], {}, {}};
            const GaussianPrediction p = predict_child(model, one, 1, data.times);
            INFO("layers " << layers << " mask " << i);
            CHECK((many[i].mean - p.mean).cwiseAbs().maxCoeff() < 1e-10);
            CHECK((many[i].variance - p.variance).cwiseAbs().maxCoeff() < 1e-10);
        }
        data.observed = {{}, {}, std::vector<bool>(t, false), {}};
        data.observed[2][0] = true;
        CHECK_THROWS_AS(predict_child_masks(model, data, 1, masks), mocapdb::InvalidArgument);
    }
}
