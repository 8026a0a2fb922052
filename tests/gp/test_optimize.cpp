// Fitting: the likelihood increases, restarts are deterministic, bad starts are statuses.
#include <catch2/catch.hpp>

#include "gp_fixtures.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/gp/experiment.hpp"
#include "mocapdb/gp/optimize.hpp"

using namespace mocapdb;
using namespace mocapdb::gp;
using namespace mocapdb::gp::test;

TEST_CASE("fitting increases the likelihood and is deterministic", "[gp][fit]") {
    ArtificialConfig config;
    config.outputs = 2;
    config.children = 4;
    config.inputs = 20;
    const HgpModel truth = artificial_generator(config, 3);
    HgpData data;
    data.times = VecX::LinSpaced(20, 0.0, 2 * kPi);
    data.children = sample_hierarchy(truth, data.times, 4, 4);
    ModelSpec spec;
    spec.kernel = KernelType::Rbf;
    const HgpModel start = initial_model(data, spec);
    const double l0 = log_likelihood(start, data, false).log_likelihood;
    FitOptions o;
    o.restarts = 2;
    o.max_iterations = 150;
    const FitResult a = fit(data, start, o);
    const FitResult b = fit(data, start, o);
    INFO("start " << l0 << " fitted " << a.log_likelihood << " status " << to_string(a.status));
    CHECK(a.log_likelihood > l0 + 10.0);
    CHECK(a.log_likelihood == b.log_likelihood);
    CHECK(a.restarts.size() == 2);
    CHECK(a.status != FitStatus::NumericalFailure);
    CHECK(log_likelihood(a.model, data, false).log_likelihood == Approx(a.log_likelihood).epsilon(1e-12));
    // The fitted model explains the data at least as well as the generating one.
    CHECK(a.log_likelihood > log_likelihood(truth, data, false).log_likelihood - 5.0);
    // One iteration: reported as max_iterations, not thrown.
    o.restarts = 1;
    o.max_iterations = 1;
    const FitResult c = fit(data, start, o);
    CHECK(c.status == FitStatus::MaxIterations);
    // MOA fits too.
    spec.hierarchical = false;
    o.max_iterations = 100;
    const FitResult m = fit(data, initial_model(data, spec), o);
    CHECK(m.status != FitStatus::NumericalFailure);
    CHECK_FALSE(m.model.hierarchical);
}

TEST_CASE("an unusable start is a status, not an exception", "[gp][fit]") {
    HgpModel model = make_model(2, true, 1, 1);
    model.noise_floor = 0.0;
    model.log_noise.setConstant(-800.0);
    for (Lmc* lmc : {&model.child, &model.parent})
        for (auto& t : lmc->terms) {
            t.W.setZero();
            t.log_kappa.setConstant(-800.0);
        }
    const HgpData data = make_data(2, 6, 2);
    FitOptions o;
    o.restarts = 2;
    o.restart_spread = 0.0;
    FitResult r;
    REQUIRE_NOTHROW(r = fit(data, model, o));
    CHECK(r.status == FitStatus::NumericalFailure);
    CHECK_FALSE(r.restarts[0].message.empty());
    o.restarts = 0;
    CHECK_THROWS_AS(fit(data, model, o), InvalidArgument);
}

TEST_CASE("artificial experiment: MOHGP interpolates a sparsely observed child better than MOA", "[gp][experiment]") {
    // A small version of the thesis's §5.1.1 test 1 (3 outputs, 5 children, 5 of 50 observed).
    ArtificialConfig config;
    config.noise = 0.001;
#ifdef MOCAPDB_SANITIZED_BUILD
    config.inputs = 25;
    config.observed = 4;
#endif
    ExperimentOptions o;
    o.runs = 2;
    o.spec.kernel = KernelType::Rbf;
    o.spec.parent_terms = o.spec.child_terms = 1;
    o.fit.max_iterations = 100;
    const ArtificialResult r = run_artificial(config, o);
    REQUIRE(r.mohgp.runs.size() == 2);
    REQUIRE(r.mohgp.smse);  // the held-out outputs vary: SMSE is defined
    REQUIRE(r.moa.smse);
    INFO("SMSE MOHGP " << r.mohgp.smse->mean << " MOA " << r.moa.smse->mean << "; MSLL MOHGP " << r.mohgp.msll.mean
                       << " MOA " << r.moa.msll.mean);
    CHECK(r.mohgp.smse->mean < r.moa.smse->mean);
    CHECK(r.mohgp.msll.mean < r.moa.msll.mean);
    CHECK(r.mohgp.smse->mean < 0.5);
    CHECK(thesis_artificial_configs().size() == 9);
}

TEST_CASE("artificial synthesis: samples resemble held-out children more than the control does", "[gp][experiment][synthesis]") {
    // The thesis's §5.2.1 setting, small: 30 inputs, 3 outputs, 5 training children.
    ArtificialConfig config;
    config.inputs = 30;
    ExperimentOptions o;
    o.spec.kernel = KernelType::Rbf;
    o.fit.max_iterations = 80;
    const SynthesisResult r = run_artificial_synthesis(config, 10, o);
    REQUIRE(r.mohgp.mlc.size() == 5);
    REQUIRE(r.control.mlc.size() == 5);
    double mohgp = 0.0, moa = 0.0, control = 0.0;
    for (std::size_t i = 0; i < 5; ++i) {
        REQUIRE(r.mohgp.mlc[i]);
        REQUIRE(r.moa.mlc[i]);
        REQUIRE(r.control.mlc[i]);
        mohgp += r.mohgp.mlc[i]->mean / 5.0;
        moa += r.moa.mlc[i]->mean / 5.0;
        control += r.control.mlc[i]->mean / 5.0;
    }
    INFO("MLC MOHGP " << mohgp << " MOA " << moa << " control " << control);
    CHECK(mohgp > control + 0.2);
    CHECK(moa > control);
    CHECK(r.mohgp.mcc[0].mean > 0.0);
}
