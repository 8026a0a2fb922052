// The precomputed synthesis kernel /sets/{set}/model/kernel (issue #16, format-v4.md §8.1): round trip
// (bit-identical variogram, the optional fit status and residual variance), a kernel stored without the
// status (as written before) loading to the same model and status, it goes with the model (put_model,
// put_aligned, put_set drop it), refusals when writing, and a corrupted stored kernel refused when
// reading, naming the group (by load_kernel_fit, by the validator and by load_motion_model, which does
// not silently refit); the factorized system's round trip, unfiltered, and as written before (deflated,
// symmetric up to rounding).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/validate.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "mocapdb/workflow/synthesis_warnings.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

const std::string kKernel = "/sets/walks/model/kernel";

/// The set's kernel fit stored in one committed session.
void store_kernel_fit(const std::filesystem::path& path, const synthesis::KernelFit& fit) {
    DatabaseWriter w(path);
    w.put_kernel_fit("walks", fit);
    w.commit();
}

// A database with a clip, a 6-sample set with 2 parameters, its aligned form (full multilinear rank)
// and a model.
struct KernelFixture {
    Clip clip = synthetic_clip(60, 3, 11);
    MotionSet set;
    AlignedSet aligned;
    compression::SetModel model;

    KernelFixture() {
        set.name = "walks";
        for (std::size_t i = 0; i < 6; ++i) set.samples.push_back({"walk", 5 * i, 5 * i + 20});
        set.parameter_names = {"speed", "turn"};
        set.parameter_units = {"cm/s", "rad"};
        set.parameters = MatX(6, 2);
        set.parameters << 100, 0.1, 110, -0.2, 120, 0.3, 130, 0.0, 105, 0.25, 125, -0.1;
        set.parameter_source = "csv:test";
        aligned = synthetic_aligned(PoseLayout(*clip.skeleton).dof_count(), 12, set);
        std::mt19937 gen(3);
        std::normal_distribution<double> noise(0.0, 1.0);
        for (Eigen::Index i = 0; i < aligned.tensor.size(); ++i) aligned.tensor.data()[i] += noise(gen);
        model = compression::fit_set_model(aligned.tensor, compression::position_error_weights(*clip.skeleton),
                                           {6, 5, 5}, tensor::TuckerMethod::Hosvd);
    }
    void write(const std::filesystem::path& path, bool with_kernel) const {
        DatabaseWriter w(path);
        w.add_clip(clip, synthetic_source("walk.bvh", "w"));
        w.put_set(set, false);
        w.put_aligned(set.name, aligned);
        w.put_model(set.name, model, {});
        if (with_kernel) w.put_kernel_fit(set.name, synthesis::fit_kernel(model, aligned, set, {}));
        w.commit();
    }
};

// Rewrites the stored kernel's attributes (what another writer might leave), with h5py
// (tests/data/damage_dataset.py).
void write_raw_kernel(const std::filesystem::path& path, const std::string& key, const std::string& family,
                      double sill) {
    char sill_text[64];
    std::snprintf(sill_text, sizeof sill_text, "%.17g", sill);
    const CommandResult r = run_command("/usr/bin/python3 " + quoted((test_data_dir() / "damage_dataset.py").string()) +
                                        " " + quoted(path.string()) + " attrs " + kKernel + " key:s=" + key +
                                        " family:s=" + family + " exponent:f=1.4 nugget:f=0 sill:f=" + sill_text +
                                        " range:f=2");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);  // python3-h5py is installed by scripts/setup.sh
}

// Sets attributes of the stored kernel ("name:s=text" or "name:f=number" each), with h5py.
void set_kernel_attributes(const std::filesystem::path& path, const std::vector<std::string>& assignments) {
    std::string args;
    for (const std::string& a : assignments) args += " " + quoted(a);
    const CommandResult r = run_command("/usr/bin/python3 " + quoted((test_data_dir() / "damage_dataset.py").string()) +
                                        " " + quoted(path.string()) + " attrs " + kKernel + args);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
}

std::pair<std::string, std::string> kernel_error(const std::filesystem::path& path) {
    try {
        Database(path).load_kernel_fit("walks");
    } catch (const StoreError& e) {
        return {e.object_path(), e.message()};
    }
    return {"(no error)", ""};
}

}  // namespace

TEST_CASE("kernel: put_kernel_fit round-trips the variogram bit for bit, it goes with the model", "[store][kernel]") {
    TempDir dir("kernel-roundtrip");
    const auto path = dir / "db.h5";
    const KernelFixture fx;
    fx.write(path, false);
    CHECK_FALSE(Database(path).load_kernel_fit("walks").has_value());  // a model stored without one

    const synthesis::KernelFit fit = synthesis::fit_kernel(fx.model, fx.aligned, fx.set, {});
    REQUIRE(fit.key != 0);
    REQUIRE(fit.exponent_loo_mse.size() ==
            static_cast<Eigen::Index>(synthesis::SynthesisOptions{}.exponent_grid.size()));  // one per candidate p
    {
        DatabaseWriter w(path);
        w.put_kernel_fit("walks", fit);
        w.put_kernel_fit("walks", fit);  // replaces
        w.commit();
    }
    const auto back = Database(path).load_kernel_fit("walks");
    REQUIRE(back.has_value());
    CHECK(back->key == fit.key);
    CHECK(back->variogram.family == fit.variogram.family);
    CHECK(back->variogram.exponent == fit.variogram.exponent);
    CHECK(back->variogram.nugget == fit.variogram.nugget);
    CHECK(back->variogram.sill == fit.variogram.sill);
    CHECK(back->variogram.range == fit.variogram.range);
    CHECK(back->exponent_loo_mse.size() == 0);  // not stored
    // The status the model built from it reports, and the residual variance behind the sill bound.
    REQUIRE(fit.assessed_status.has_value());
    CHECK(fit.residual_variance > 0.0);
    CHECK(back->assessed_status == fit.assessed_status);
    CHECK(back->residual_variance == fit.residual_variance);
    // Every sample overlaps its neighbours (windows of one clip): no fold can leave one out with its twins,
    // so no predictor was chosen and the model uses kriging.
    CHECK_FALSE(fit.predictor.has_value());
    CHECK_FALSE(back->predictor.has_value());
    const ValidationReport report = validate_database(path);
    INFO(all_violations(report));
    CHECK(report.ok());

    // A stored model uses it: the same variogram, no refit, the stored status.
    const auto loaded = workflow::load_motion_model(Database(path), "walks");
    CHECK(loaded->report().kernel_precomputed);
    CHECK(loaded->kernel_fit().key == fit.key);
    CHECK(loaded->report().fit_status == *fit.assessed_status);
    CHECK(loaded->kernel_fit().residual_variance == fit.residual_variance);

    {
        DatabaseWriter w(path);
        w.put_model("walks", fx.model, {});  // a new model: the old kernel described the old one
        CHECK_FALSE(w.view().load_kernel_fit("walks").has_value());
        w.put_kernel_fit("walks", fit);
        w.put_aligned("walks", fx.aligned);  // drops the model and its kernel
        CHECK_FALSE(w.view().load_kernel_fit("walks").has_value());
        CHECK_THROWS_WITH(w.put_kernel_fit("walks", fit), Contains("the set has no stored model"));
        CHECK_THROWS_AS(w.view().load_kernel_fit("nope"), StoreError);
    }
}

TEST_CASE("kernel: the cross-validated predictor round-trips, is used by the loaded model and is checked when read",
          "[store][kernel]") {
    TempDir dir("kernel-predictor");
    const auto path = dir / "db.h5";
    const KernelFixture fx;
    fx.write(path, false);
    synthesis::KernelFit fit = synthesis::fit_kernel(fx.model, fx.aligned, fx.set, {});
    synthesis::PredictorChoice choice;
    choice.chosen = synthesis::Predictor::Trend;
    choice.scores = {{synthesis::Predictor::Kriging, 2.5}, {synthesis::Predictor::Rbf, 3.25}, {synthesis::Predictor::Trend, 2.0}};
    choice.folds = 4;
    choice.samples = 6;
    fit.predictor = choice;
    store_kernel_fit(path, fit);
    const auto back = Database(path).load_kernel_fit("walks");
    REQUIRE(back->predictor.has_value());
    CHECK(back->predictor->chosen == synthesis::Predictor::Trend);
    REQUIRE(back->predictor->scores.size() == 3);
    for (std::size_t k = 0; k < 3; ++k) {
        CHECK(back->predictor->scores[k].predictor == choice.scores[k].predictor);
        CHECK(back->predictor->scores[k].cv_rms == choice.scores[k].cv_rms);
    }
    CHECK(back->predictor->folds == 4);
    CHECK(back->predictor->samples == 6);
    const ValidationReport report = validate_database(path);
    INFO(all_violations(report));
    CHECK(report.ok());

    // The loaded model blends with the stored choice unless told otherwise; rho stays the kriging kernel's.
    const auto loaded = workflow::load_motion_model(Database(path), "walks");
    CHECK(loaded->report().predictor == synthesis::Predictor::Trend);
    REQUIRE(loaded->report().predictor_choice.has_value());
    synthesis::SynthesisOptions kriging_options;
    kriging_options.predictor = synthesis::Predictor::Kriging;
    const auto kriged = workflow::load_motion_model(Database(path), "walks", kriging_options);
    CHECK(kriged->report().predictor == synthesis::Predictor::Kriging);
    const VecX c = fx.set.parameters.row(2).transpose();
    CHECK(loaded->reliability(c) == kriged->reliability(c));
    synthesis::Workspace ws;
    VecX w_trend(6), w_kriging(6);
    loaded->weights(c, w_trend, ws);
    kriged->weights(c, w_kriging, ws);
    CHECK(w_trend.sum() == Approx(1.0));
    CHECK((w_trend - w_kriging).norm() > 1e-3);  // the trend does not interpolate: not kriging's e_2

    set_kernel_attributes(path, {"predictor:s=spline"});
    auto e = kernel_error(path);
    CHECK(e.first == kKernel);
    CHECK_THAT(e.second, Contains("'predictor'") && Contains("spline"));
    set_kernel_attributes(path, {"predictor:s=rbf", "predictor_folds:i=9"});
    e = kernel_error(path);
    CHECK(e.first == kKernel);
    CHECK_THAT(e.second, Contains("predictor_folds"));
}

TEST_CASE("kernel: an averaged predictor round-trips with its weights and errors, blends the loaded model, is checked",
          "[store][kernel]") {
    TempDir dir("kernel-average");
    const auto path = dir / "db.h5";
    const KernelFixture fx;
    fx.write(path, false);
    synthesis::KernelFit fit = synthesis::fit_kernel(fx.model, fx.aligned, fx.set, {});
    using synthesis::Predictor;
    synthesis::PredictorChoice choice;
    choice.chosen = Predictor::Average;
    choice.scores = {{Predictor::Kriging, 2.5, 0.0, 0.5}, {Predictor::Rbf, 2.625, 0.25, 0.5}, {Predictor::Trend, 4.0, 0.5, 0.0}};
    choice.folds = 4;
    choice.samples = 6;
    fit.predictor = choice;
    store_kernel_fit(path, fit);
    const auto back = Database(path).load_kernel_fit("walks");
    REQUIRE(back->predictor.has_value());
    CHECK(back->predictor->chosen == Predictor::Average);
    REQUIRE(back->predictor->scores.size() == 3);
    for (std::size_t k = 0; k < 3; ++k) {
        CHECK(back->predictor->scores[k].cv_se == choice.scores[k].cv_se);
        CHECK(back->predictor->scores[k].weight == choice.scores[k].weight);
    }
    CHECK(back->predictor->members() == std::vector<Predictor>{Predictor::Kriging, Predictor::Rbf});
    const ValidationReport report = validate_database(path);
    INFO(all_violations(report));
    CHECK(report.ok());

    // The loaded model blends with the mean of kriging's and RBF's weights.
    const auto loaded = workflow::load_motion_model(Database(path), "walks");
    CHECK(loaded->report().predictor == Predictor::Average);
    const VecX c = 0.5 * (fx.set.parameters.row(1) + fx.set.parameters.row(2)).transpose();
    VecX expected = VecX::Zero(6);
    for (const Predictor p : {Predictor::Kriging, Predictor::Rbf}) {
        synthesis::SynthesisOptions one;
        one.predictor = p;
        synthesis::Workspace ws;
        VecX w(6);
        workflow::load_motion_model(Database(path), "walks", one)->weights(c, w, ws);
        expected += 0.5 * w;
    }
    synthesis::Workspace ws;
    VecX got(6);
    loaded->weights(c, got, ws);
    CHECK((got - expected).norm() < 1e-12);

    // A stored choice of one predictor read as an average has a single positive weight: refused.
    fit.predictor->chosen = Predictor::Rbf;
    fit.predictor->scores[0].weight = 0.0;
    fit.predictor->scores[1].weight = 1.0;
    store_kernel_fit(path, fit);
    CHECK(Database(path).load_kernel_fit("walks")->predictor->chosen == Predictor::Rbf);
    set_kernel_attributes(path, {"predictor:s=average"});
    const auto e = kernel_error(path);
    CHECK(e.first == kKernel);
    CHECK_THAT(e.second, Contains("predictor_weights") && Contains("at least 2"));
}

TEST_CASE("kernel: the calibrated warning threshold round-trips, warns the loaded model and is checked when read",
          "[store][kernel]") {
    TempDir dir("kernel-edge");
    const auto path = dir / "db.h5";
    const KernelFixture fx;
    fx.write(path, false);
    synthesis::KernelFit fit = synthesis::fit_kernel(fx.model, fx.aligned, fx.set, {});
    synthesis::EdgeWarning edge;
    edge.variance_ratio = 1.0 / 3.0;
    edge.beyond_sd = 0.75;
    edge.tolerance_share = 0.25;
    edge.probes = 40;
    edge.misses = 7;
    edge.detection = 6.0 / 7.0;
    edge.false_alarms = 0.05;
    edge.neighbours = 5;  // the vote rule and the calibration's requests it reads
    edge.votes = 3;
    edge.probe_requests = MatX::Random(40, fx.set.parameters.cols());
    for (std::size_t i = 0; i < 40; ++i) edge.probe_missed.push_back(i % 6 == 0 ? 1 : 0);
    fit.edge_warning = edge;
    store_kernel_fit(path, fit);
    const auto back = Database(path).load_kernel_fit("walks");
    REQUIRE(back->edge_warning.has_value());
    CHECK(back->edge_warning->variance_ratio == edge.variance_ratio);
    CHECK(back->edge_warning->beyond_sd == edge.beyond_sd);
    CHECK(back->edge_warning->tolerance_share == edge.tolerance_share);
    CHECK(back->edge_warning->probes == 40);
    CHECK(back->edge_warning->misses == 7);
    CHECK(back->edge_warning->detection == edge.detection);
    CHECK(back->edge_warning->false_alarms == edge.false_alarms);
    CHECK(back->edge_warning->neighbours == 5);
    CHECK(back->edge_warning->votes == 3);
    CHECK(back->edge_warning->probe_requests == edge.probe_requests);
    CHECK(back->edge_warning->probe_missed == edge.probe_missed);
    CHECK(validate_database(path).ok());
    // The loaded model flags by the stored thresholds: rho below 2/3 instead of the fixed 0.5.
    const auto loaded = workflow::load_motion_model(Database(path), "walks");
    CHECK(workflow::edge_warning(*loaded).variance_ratio == edge.variance_ratio);
    CHECK(workflow::edge_warning(*loaded).beyond_sd == edge.beyond_sd);

    {
        DatabaseWriter w(path);
        synthesis::KernelFit bad = fit;
        bad.edge_warning->misses = 41;
        CHECK_THROWS_WITH(w.put_kernel_fit("walks", bad), Contains("edge warning"));
        bad = fit;
        bad.edge_warning->variance_ratio = -1.0;
        CHECK_THROWS_WITH(w.put_kernel_fit("walks", bad), Contains("edge warning"));
        bad = fit;
        bad.edge_warning->probe_missed.pop_back();
        CHECK_THROWS_WITH(w.put_kernel_fit("walks", bad), Contains("vote rule"));
    }
    set_kernel_attributes(path, {"edge_votes:i=6"});
    auto votes = kernel_error(path);
    CHECK(votes.first == kKernel);
    CHECK_THAT(votes.second, Contains("edge_votes"));
    set_kernel_attributes(path, {"edge_votes:i=3"});
    set_kernel_attributes(path, {"edge_variance_ratio:f=-0.5"});
    auto e = kernel_error(path);
    CHECK(e.first == kKernel);
    CHECK_THAT(e.second, Contains("edge_variance_ratio"));
    set_kernel_attributes(path, {"edge_variance_ratio:f=0.5", "edge_misses:i=41"});
    e = kernel_error(path);
    CHECK(e.first == kKernel);
    CHECK_THAT(e.second, Contains("edge_misses"));
    set_kernel_attributes(path, {"edge_misses:i=7", "edge_detection:f=1.5"});
    e = kernel_error(path);
    CHECK_THAT(e.second, Contains("edge_detection"));
    set_kernel_attributes(path, {"edge_detection:f=0.5", "edge_beyond_sd:f=inf"});
    e = kernel_error(path);
    CHECK_THAT(e.second, Contains("edge_beyond_sd"));
}

TEST_CASE("kernel: put_kernel_fit refuses a fit without a key or with an invalid variogram", "[store][kernel]") {
    TempDir dir("kernel-refuse");
    const auto path = dir / "db.h5";
    const KernelFixture fx;
    fx.write(path, false);
    const synthesis::KernelFit good = synthesis::fit_kernel(fx.model, fx.aligned, fx.set, {});
    DatabaseWriter w(path);
    synthesis::KernelFit bad = good;
    bad.key = 0;
    CHECK_THROWS_WITH(w.put_kernel_fit("walks", bad), Contains("no key"));
    bad = good;
    bad.variogram.sill = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(w.put_kernel_fit("walks", bad), Contains("sill"));
    bad = good;
    bad.variogram.nugget = 0.0;
    bad.variogram.sill = 0.0;
    CHECK_THROWS_WITH(w.put_kernel_fit("walks", bad), Contains("nugget + sill must be > 0"));
}

TEST_CASE("kernel: a corrupted stored kernel is refused naming its group", "[store][kernel]") {
    TempDir dir("kernel-corrupt");
    const auto path = dir / "db.h5";
    const KernelFixture fx;
    fx.write(path, true);
    const synthesis::KernelFit fit = *Database(path).load_kernel_fit("walks");
    char key[20];
    std::snprintf(key, sizeof key, "%016llx", static_cast<unsigned long long>(fit.key));

    write_raw_kernel(path, key, "stable", std::numeric_limits<double>::quiet_NaN());
    auto e = kernel_error(path);
    CHECK(e.first == kKernel);
    CHECK_THAT(e.second, Contains("sill"));
    // Synthesis refuses the file rather than silently refitting.
    CHECK_THROWS_WITH(workflow::load_motion_model(Database(path), "walks"), Contains(kKernel));
    const ValidationReport report = validate_database(path);
    CHECK(has_violation(report, kKernel, "sill"));

    write_raw_kernel(path, key, "stable", -1.0);
    CHECK(kernel_error(path).first == kKernel);
    write_raw_kernel(path, key, "gaussian", 1.0);
    e = kernel_error(path);
    CHECK(e.first == kKernel);
    CHECK_THAT(e.second, Contains("family"));
    write_raw_kernel(path, "12345", "stable", 1.0);
    e = kernel_error(path);
    CHECK(e.first == kKernel);
    CHECK_THAT(e.second, Contains("16 lowercase hexadecimal digits"));
    write_raw_kernel(path, "0000000000000000", "stable", 1.0);
    CHECK(kernel_error(path).first == kKernel);

    // A well-formed kernel of other inputs (another key) is ignored: the model fits its own.
    write_raw_kernel(path, "00000000000000ab", "stable", 1.0);
    REQUIRE(kernel_error(path).first == "(no error)");
    const auto loaded = workflow::load_motion_model(Database(path), "walks");
    CHECK_FALSE(loaded->report().kernel_precomputed);
    CHECK(loaded->kernel_fit().key == fit.key);
    CHECK(loaded->kernel_fit().variogram.sill == fit.variogram.sill);
}

TEST_CASE("kernel: a kernel stored without its fit status loads to the same model and status", "[store][kernel]") {
    TempDir dir("kernel-no-status");
    const auto with_path = dir / "with.h5";
    const auto without_path = dir / "without.h5";
    const KernelFixture fx;
    fx.write(with_path, true);
    fx.write(without_path, false);
    synthesis::KernelFit old_style = synthesis::fit_kernel(fx.model, fx.aligned, fx.set, {});
    REQUIRE(old_style.assessed_status.has_value());
    const kriging::FitStatus status = *old_style.assessed_status;
    old_style.assessed_status.reset();  // what writers before the status was stored left
    {
        DatabaseWriter w(without_path);
        w.put_kernel_fit("walks", old_style);
        w.commit();
    }
    const auto back = Database(without_path).load_kernel_fit("walks");
    REQUIRE(back.has_value());
    CHECK_FALSE(back->assessed_status.has_value());
    CHECK(back->residual_variance == 0.0);
    const ValidationReport report = validate_database(without_path);
    INFO(all_violations(report));
    CHECK(report.ok());

    // The model recomputes the status: the one stored beside the other file's kernel, and the same model.
    const auto with = workflow::load_motion_model(Database(with_path), "walks");
    const auto without = workflow::load_motion_model(Database(without_path), "walks");
    CHECK(without->report().kernel_precomputed);
    CHECK(without->report().fit_status == status);
    CHECK(with->report().fit_status == status);
    CHECK(without->kernel_fit().variogram.range == with->kernel_fit().variogram.range);
    const Eigen::Vector2d c(117.0, 0.05);
    CHECK(without->pose(c, 4.5) == with->pose(c, 4.5));
}

TEST_CASE("kernel: the stored fit status is the model's when the key matches, malformed ones are refused",
          "[store][kernel]") {
    TempDir dir("kernel-status");
    const auto path = dir / "db.h5";
    const KernelFixture fx;
    fx.write(path, true);
    const synthesis::KernelFit fit = *Database(path).load_kernel_fit("walks");
    REQUIRE(fit.assessed_status.has_value());

    // Another stored status under the same key is taken as it is (the key says it belongs to these inputs).
    const kriging::FitStatus other = *fit.assessed_status == kriging::FitStatus::PureNugget
                                         ? kriging::FitStatus::RangeAtBound
                                         : kriging::FitStatus::PureNugget;
    set_kernel_attributes(path, {std::string("fit_status:s=") + kriging::to_string(other)});
    CHECK(workflow::load_motion_model(Database(path), "walks")->report().fit_status == other);

    set_kernel_attributes(path, {"fit_status:s=fine"});
    auto e = kernel_error(path);
    CHECK(e.first == kKernel);
    CHECK_THAT(e.second, Contains("fit_status"));
    CHECK_THROWS_WITH(workflow::load_motion_model(Database(path), "walks"), Contains(kKernel));
    CHECK(has_violation(validate_database(path), kKernel, "fit_status"));

    set_kernel_attributes(path, {"fit_status:s=ok", "residual_variance:f=-1"});
    e = kernel_error(path);
    CHECK(e.first == kKernel);
    CHECK_THAT(e.second, Contains("residual_variance"));

    // One without the other.
    const auto half_path = dir / "half.h5";
    fx.write(half_path, false);
    synthesis::KernelFit bare = fit;
    bare.assessed_status.reset();
    {
        DatabaseWriter w(half_path);
        w.put_kernel_fit("walks", bare);
        w.commit();
    }
    set_kernel_attributes(half_path, {"fit_status:s=ok"});
    e = kernel_error(half_path);
    CHECK(e.first == kKernel);
    CHECK_THAT(e.second, Contains("residual_variance"));

    // The writer refuses an unusable residual variance with a status.
    DatabaseWriter w(half_path);
    synthesis::KernelFit bad = fit;
    bad.residual_variance = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(w.put_kernel_fit("walks", bad), Contains("residual variance"));
}

namespace {

// Runs tests/data/damage_dataset.py on the stored system in `mode` ("deflate" or "filters"); its output.
std::string on_system(const std::filesystem::path& path, const std::string& mode) {
    const CommandResult r = run_command("/usr/bin/python3 " + quoted((test_data_dir() / "damage_dataset.py").string()) +
                                        " " + quoted(path.string()) + " " + mode + " " + kKernel +
                                        "/covariance_inverse");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    return r.output;
}

}  // namespace

TEST_CASE("kernel: the factorized system round-trips bit for bit, unfiltered; a deflated or asymmetric one as "
          "written before loads the same",
          "[store][kernel]") {
    TempDir dir("kernel-system");
    const auto path = dir / "db.h5";
    const KernelFixture fx;
    fx.write(path, false);
    const synthesis::KernelFit fit = synthesis::fit_kernel(fx.model, fx.aligned, fx.set, {});
    REQUIRE(fit.system);
    const MatX& inverse = fit.system->inverse;
    CHECK(inverse == inverse.transpose());  // exactly symmetric: stored as the column-major buffer is
    const auto stored = [&path]() {
        const auto back = Database(path).load_kernel_fit("walks");
        REQUIRE(back.has_value());
        REQUIRE(back->system);
        return *back->system;
    };
    store_kernel_fit(path, fit);
    CHECK(on_system(path, "filters") == "fletcher32\n");  // deflate does not shrink these doubles
    kriging::CovarianceInverse back = stored();
    CHECK(back.inverse == inverse);
    CHECK(back.factorization == fit.system->factorization);
    CHECK(back.jitter == fit.system->jitter);
    CHECK(back.rcond == fit.system->rcond);
    const ValidationReport report = validate_database(path);
    INFO(all_violations(report));
    CHECK(report.ok());

    // As written before 2026-12-06: shuffle + deflate, and symmetric only up to rounding (the reader
    // transposes what is not symmetric back: the value at (0, 1) stays there).
    synthesis::KernelFit asymmetric = fit;
    kriging::CovarianceInverse skewed = *fit.system;
    skewed.inverse(0, 1) = std::nextafter(skewed.inverse(0, 1), std::numeric_limits<double>::infinity());
    asymmetric.system = std::make_shared<const kriging::CovarianceInverse>(skewed);
    {
        DatabaseWriter w(path);
        w.put_kernel_fit("walks", asymmetric);
        w.commit();
    }
    on_system(path, "deflate");
    CHECK(on_system(path, "filters") == "shuffle,deflate,fletcher32\n");
    back = stored();
    CHECK(back.inverse == skewed.inverse);
    CHECK(back.inverse(0, 1) != back.inverse(1, 0));
    const auto loaded = workflow::load_motion_model(Database(path), "walks");
    CHECK(loaded->report().system_precomputed);
}
