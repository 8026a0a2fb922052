// Format version 2: a set's Tucker model in /sets/{set}/model. Round trip (bit-identical), replacement,
// models dropped with the tensor they describe, refusals, malformed models (tests/data/bad-model-*.h5
// made by tests/data/make_bad_fixtures.py), validation and the CLI's listing.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "mini_json.hpp"
#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/storage_extents.hpp"
#include "mocapdb/store/validate.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

MotionSet four_sample_set() {
    MotionSet set;
    set.name = "walks";
    set.samples = {{"walk", 0, 20}, {"walk", 5, 30}, {"walk", 10, 35}, {"walk", 15, 40}};
    set.parameter_names = {"speed"};
    set.parameter_units = {"cm/s"};
    set.parameters = MatX(4, 1);
    set.parameters << 100.0, 110.0, 120.0, 130.0;
    set.parameter_source = "csv:test";
    return set;
}

// An aligned set whose tensor has full multilinear rank (smooth values plus seeded noise).
AlignedSet noisy_aligned(std::size_t dofs, std::size_t frames, const MotionSet& set, unsigned seed) {
    AlignedSet a = synthetic_aligned(dofs, frames, set);
    std::mt19937 gen(seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    for (Eigen::Index i = 0; i < a.tensor.size(); ++i) a.tensor.data()[i] += noise(gen);
    return a;
}

struct Fixture {
    Clip clip = synthetic_clip(40, 3, 7);
    std::size_t dofs = PoseLayout(*clip.skeleton).dof_count();
    MotionSet set = four_sample_set();
    AlignedSet aligned = noisy_aligned(dofs, 12, set, 1);
    VecX weight = compression::position_error_weights(*clip.skeleton);

    // A database with the clip, the set and its aligned form.
    void write(const std::filesystem::path& path) const {
        DatabaseWriter w(path);
        w.add_clip(clip, synthetic_source("walk.bvh", "w"));
        w.put_set(set, false);
        w.put_aligned(set.name, aligned);
        w.commit();
    }
    compression::SetModel model(const tensor::Ranks& ranks, tensor::TuckerMethod method,
                                const Tensor3* tensor = nullptr) const {
        return compression::fit_set_model(tensor ? *tensor : aligned.tensor, weight, ranks, method);
    }
};

bool same_bits(const Tensor3& a, const Tensor3& b) {
    if (a.dimensions() != b.dimensions()) return false;
    for (Eigen::Index i = 0; i < a.size(); ++i)
        if (a.data()[i] != b.data()[i]) return false;
    return true;
}

void check_identical(const StoredModel& back, const compression::SetModel& m, const ModelFigures& fig) {
    const tensor::TuckerModel& t = m.tucker;
    const tensor::TuckerModel& b = back.model.tucker;
    CHECK(b.ranks == t.ranks);
    CHECK(same_bits(b.core, t.core));
    for (int k = 0; k < 3; ++k) CHECK(b.U[static_cast<std::size_t>(k)] == t.U[static_cast<std::size_t>(k)]);
    CHECK(back.model.mean == m.mean);
    CHECK(back.model.weight == m.weight);
    CHECK(b.method == t.method);
    CHECK(b.status == t.status);
    CHECK(b.iterations == t.iterations);
    CHECK(b.fit == t.fit);
    CHECK(b.error_bound == t.error_bound);
    CHECK(b.data_norm == t.data_norm);
    CHECK(b.fit_history == std::vector<double>{t.fit});
    CHECK(back.figures.dof_rmse == fig.dof_rmse);
    CHECK(back.figures.rmse_cm == fig.rmse_cm);
    CHECK(back.figures.mean_cm == fig.mean_cm);
    CHECK(back.figures.max_cm == fig.max_cm);
    CHECK(back.figures.p99_cm == fig.p99_cm);
}

// Puts `m` as the model of set "walks" in its own write session.
void store_model(const std::filesystem::path& db_path, const compression::SetModel& m, const ModelFigures& fig) {
    DatabaseWriter w(db_path);
    w.put_model("walks", m, fig);
    w.commit();
}

// The StoreError of load_model on a fixture: its path and message.
std::pair<std::string, std::string> load_error(const std::filesystem::path& file) {
    try {
        Database(file).load_model("tiny_set");
    } catch (const StoreError& e) {
        return {e.object_path(), e.what()};
    }
    return {"(no error)", ""};
}

}  // namespace

TEST_CASE("model: put_model, commit, load_model round-trips every double exactly", "[store][model]") {
    TempDir dir("model-roundtrip");
    const auto db_path = dir / "db.h5";
    const Fixture fx;
    fx.write(db_path);
    const compression::SetModel m = fx.model({5, 4, 3}, tensor::TuckerMethod::Hooi);
    REQUIRE(m.tucker.iterations > 0);
    const ModelFigures fig{0.125, 1.5, 1.25, 3.75, 3.5};
    {
        DatabaseWriter w(db_path);
        CHECK_FALSE(w.view().load_model("walks").has_value());
        w.put_model("walks", m, fig);
        const auto in_session = w.view().load_model("walks");  // the session reads what it wrote
        REQUIRE(in_session.has_value());
        check_identical(*in_session, m, fig);
        w.commit();
    }
    const Database db(db_path);
    CHECK(db.format_version() == kDatabaseFormatVersion);
    const auto back = db.load_model("walks");
    REQUIRE(back.has_value());
    check_identical(*back, m, fig);
    // It reconstructs what the model reconstructs (same bits in, same arithmetic).
    CHECK(same_bits(back->model.reconstruct(), m.reconstruct()));

    const auto sets = db.sets();
    REQUIRE(sets.size() == 1);
    CHECK(sets[0].model);
    CHECK(sets[0].model_ranks == std::array<std::size_t, 3>{5, 4, 3});
    CHECK(sets[0].model_stored_bytes > 0);
    CHECK(sets[0].model_stored_bytes < db.file_size());
    CHECK_THROWS_AS(db.load_model("nope"), StoreError);

    const ValidationReport r = validate_database(db_path);
    INFO(all_violations(r));
    CHECK(r.ok());
    CHECK(r.format_version == kDatabaseFormatVersion);

    // The CLI lists the ranks.
    const CommandResult list = run_cli("set list " + quoted(db_path.string()));
    INFO(list.output);
    CHECK(list.exit_code == 0);
    CHECK(list.output.find("aligned, model 5x4x3") != std::string::npos);
    const CommandResult json = run_cli("set list --json " + quoted(db_path.string()));
    REQUIRE(json.exit_code == 0);
    const Json listed = parse_json(json.out);
    REQUIRE(listed.items.size() == 1);
    CHECK(listed[0]["model"].boolean);
    REQUIRE(listed[0]["model_ranks"].items.size() == 3);
    CHECK(listed[0]["model_ranks"][0].number == 5);
    CHECK(listed[0]["model_ranks"][2].number == 3);
    const CommandResult info = run_cli("info " + quoted(db_path.string()));
    INFO(info.output);
    CHECK(info.exit_code == 0);
    CHECK(info.output.find("format      mocapdb " + std::to_string(kDatabaseFormatVersion)) != std::string::npos);
    CHECK(info.output.find("5 x 4 x 3") != std::string::npos);
    const CommandResult info_json = run_cli("info --json " + quoted(db_path.string()));
    REQUIRE(info_json.exit_code == 0);
    const Json doc = parse_json(info_json.out);
    CHECK(doc["format_version"].number == kDatabaseFormatVersion);
    CHECK(doc["sets"][0]["model"].boolean);
    CHECK(doc["sets"][0]["model_ranks"][1].number == 4);
    CHECK(doc["sets"][0]["model_stored_bytes"].number > 0);
}

TEST_CASE("model: a model of several MB, its chunks filtered on the machine's cores, round-trips exactly (#16)",
          "[store][model]") {
    // From 4 MB on, a deflated dataset's chunks are shuffled, deflated and checksummed by the library
    // (several at once) and written raw: HDF5 reads them back through its standard filters, so a
    // wrong checksum, shuffle or stream fails the load or the comparison here.
    TempDir dir("model-large");
    const auto db_path = dir / "db.h5";
    Fixture fx;
    const Eigen::Index samples = 6001;  // not a multiple of the chunk's rows: a zero-padded edge chunk
    fx.set.samples.clear();
    fx.set.parameters = MatX(samples, 1);
    for (Eigen::Index k = 0; k < samples; ++k) {
        fx.set.samples.push_back({"walk", static_cast<std::size_t>(k % 20), static_cast<std::size_t>(k % 20 + 20)});
        fx.set.parameters(k, 0) = 100.0 + static_cast<double>(k);
    }
    fx.aligned = noisy_aligned(fx.dofs, 12, fx.set, 3);
    REQUIRE(fx.aligned.tensor.size() * 8 >= 4 * 1024 * 1024);
    fx.write(db_path);
    const compression::SetModel m = fx.model({4, 6, 90}, tensor::TuckerMethod::Hosvd);
    REQUIRE(m.tucker.U[2].size() * 8 >= 4 * 1024 * 1024);
    const ModelFigures fig{0.5, 1.0, 0.75, 2.0, 1.5};
    store_model(db_path, m, fig);
    const Database db(db_path);
    const auto back = db.load_model("walks");
    REQUIRE(back.has_value());
    check_identical(*back, m, fig);
    const auto aligned = db.load_aligned("walks");
    REQUIRE(aligned.has_value());
    CHECK(same_bits(aligned->tensor, fx.aligned.tensor));
    CHECK(validate_database(db_path).ok());
    // Seeded noise deflates poorly: the chunks after the first 4 (about 256 KiB each, deflated to
    // decide) are stored at deflate level 0, each larger than any deflated one; the round trip above
    // read them.
    const std::vector<ByteExtent> chunks = dataset_extents(db_path, "/sets/walks/model/sample_basis");
    REQUIRE(chunks.size() > 8);
    std::uint64_t deflated = 0, stored = std::numeric_limits<std::uint64_t>::max();
    for (std::size_t i = 0; i < 4; ++i) deflated = std::max(deflated, chunks[i].size);
    for (std::size_t i = 4; i < chunks.size(); ++i) stored = std::min(stored, chunks[i].size);
    CHECK(stored > deflated);
}

TEST_CASE("model: a large dataset that deflates well stays deflated (#16)", "[store][model]") {
    // The other side of the level-0 fallback: an aligned tensor of several MB whose values are
    // quarters (few distinct doubles) keeps deflate on every chunk, and reads back exactly.
    TempDir dir("model-deflated");
    const auto db_path = dir / "db.h5";
    Fixture fx;
    const Eigen::Index samples = 6001;
    fx.set.samples.clear();
    fx.set.parameters = MatX(samples, 1);
    for (Eigen::Index k = 0; k < samples; ++k) {
        fx.set.samples.push_back({"walk", static_cast<std::size_t>(k % 20), static_cast<std::size_t>(k % 20 + 20)});
        fx.set.parameters(k, 0) = 100.0 + static_cast<double>(k);
    }
    fx.aligned = synthetic_aligned(fx.dofs, 12, fx.set);
    for (Eigen::Index i = 0; i < fx.aligned.tensor.size(); ++i)
        fx.aligned.tensor.data()[i] = std::round(4.0 * fx.aligned.tensor.data()[i]) / 4.0;
    const auto raw = static_cast<std::uint64_t>(fx.aligned.tensor.size()) * 8;
    REQUIRE(raw >= 4 * 1024 * 1024);
    fx.write(db_path);
    std::uint64_t stored = 0;
    for (const ByteExtent& e : dataset_extents(db_path, "/sets/walks/aligned/tensor")) stored += e.size;
    CHECK(stored < raw / 2);
    const auto aligned = Database(db_path).load_aligned("walks");
    REQUIRE(aligned.has_value());
    CHECK(same_bits(aligned->tensor, fx.aligned.tensor));
}

TEST_CASE("model: put_model replaces a stored model", "[store][model]") {
    TempDir dir("model-replace");
    const auto db_path = dir / "db.h5";
    const Fixture fx;
    fx.write(db_path);
    const compression::SetModel first = fx.model({6, 6, 3}, tensor::TuckerMethod::Hosvd);
    const compression::SetModel second = fx.model({2, 3, 1}, tensor::TuckerMethod::StHosvd);
    const ModelFigures fig1{1, 2, 3, 4, 5}, fig2{0.5, 0.25, 0.125, 2, 1};
    store_model(db_path, first, fig1);
    const std::uint64_t size_first = database_disk_bytes(db_path);
    store_model(db_path, second, fig2);
    const Database db(db_path);
    const auto back = db.load_model("walks");
    REQUIRE(back.has_value());
    check_identical(*back, second, fig2);
    CHECK(db.sets()[0].model_ranks == std::array<std::size_t, 3>{2, 3, 1});
    // The old model's space was reclaimed (the file was rewritten compactly).
    CHECK(database_disk_bytes(db_path) < size_first);
    CHECK(validate_database(db_path).ok());
}

TEST_CASE("model: put_aligned, put_set(replace) and remove_set drop the model", "[store][model]") {
    TempDir dir("model-drop");
    const auto db_path = dir / "db.h5";
    const Fixture fx;
    fx.write(db_path);
    const compression::SetModel m = fx.model({3, 3, 2}, tensor::TuckerMethod::Hosvd);
    {
        DatabaseWriter w(db_path);
        w.put_model("walks", m, {});
        w.put_aligned("walks", noisy_aligned(fx.dofs, 12, fx.set, 2));
        CHECK_FALSE(w.view().load_model("walks").has_value());
        CHECK_FALSE(w.view().sets()[0].model);
        w.put_model("walks", m, {});  // same shapes: allowed again
        w.commit();
    }
    REQUIRE(Database(db_path).load_model("walks").has_value());
    {
        DatabaseWriter w(db_path);
        w.put_set(fx.set, true);
        CHECK_FALSE(w.view().load_model("walks").has_value());
        CHECK_FALSE(w.view().load_aligned("walks").has_value());
        CHECK_THROWS_WITH(w.put_model("walks", m, {}), Catch::Contains("the set is not aligned"));
        w.commit();
    }
    CHECK_FALSE(Database(db_path).load_model("walks").has_value());
    CHECK(validate_database(db_path).ok());
}

TEST_CASE("model: put_model refuses models that do not fit the aligned set", "[store][model]") {
    TempDir dir("model-refuse");
    const auto db_path = dir / "db.h5";
    const Fixture fx;
    {
        DatabaseWriter w(db_path);
        w.add_clip(fx.clip, synthetic_source("walk.bvh", "w"));
        w.put_set(fx.set, false);
        w.commit();
    }
    const compression::SetModel good = fx.model({3, 3, 2}, tensor::TuckerMethod::Hosvd);
    DatabaseWriter w(db_path);
    CHECK_THROWS_WITH(w.put_model("nope", good, {}), Catch::Contains("motion set 'nope' is not stored"));
    CHECK_THROWS_AS(w.put_model("walks", good, {}), InvalidArgument);
    CHECK_THROWS_WITH(w.put_model("walks", good, {}), Catch::Contains("model of 'walks': the set is not aligned"));
    w.put_aligned("walks", fx.aligned);

    MotionSet other = fx.set;
    const Tensor3 more_dofs = noisy_aligned(fx.dofs + 3, 12, fx.set, 3).tensor;
    const compression::SetModel wrong_d = compression::fit_set_model(
        more_dofs, VecX::Ones(static_cast<Eigen::Index>(fx.dofs + 3)), {3, 3, 2}, tensor::TuckerMethod::Hosvd);
    CHECK_THROWS_WITH(w.put_model("walks", wrong_d, {}),
                      Catch::Contains("D (dofs) is " + std::to_string(fx.dofs + 3) + ", but the aligned tensor has " +
                                      std::to_string(fx.dofs)));
    const Tensor3 more_frames = noisy_aligned(fx.dofs, 13, fx.set, 4).tensor;
    CHECK_THROWS_WITH(w.put_model("walks", fx.model({3, 3, 2}, tensor::TuckerMethod::Hosvd, &more_frames), {}),
                      Catch::Contains("T (aligned frames) is 13, but the aligned tensor has 12"));
    other.samples.pop_back();
    const Tensor3 fewer_samples = noisy_aligned(fx.dofs, 12, other, 5).tensor;
    CHECK_THROWS_WITH(w.put_model("walks", fx.model({3, 3, 2}, tensor::TuckerMethod::Hosvd, &fewer_samples), {}),
                      Catch::Contains("N (samples) is 3, but the aligned tensor has 4"));

    compression::SetModel bad_weight = good;
    bad_weight.weight(0) = -1.0;
    CHECK_THROWS_WITH(w.put_model("walks", bad_weight, {}), Catch::Contains("weights must be finite and > 0"));
    compression::SetModel bad_core = good;
    bad_core.tucker.core = Tensor3(3, 3, 1);
    bad_core.tucker.core.setZero();
    CHECK_THROWS_AS(w.put_model("walks", bad_core, {}), InvalidArgument);
    compression::SetModel nan_basis = good;
    nan_basis.tucker.U[1](0, 0) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(w.put_model("walks", nan_basis, {}), InvalidArgument);
    CHECK_THROWS_WITH(w.put_model("walks", good, {std::numeric_limits<double>::infinity(), 0, 0, 0, 0}),
                      Catch::Contains("figures.dof_rmse must be finite and >= 0"));
    CHECK_THROWS_WITH(w.put_model("walks", good, {0, -1, 0, 0, 0}), Catch::Contains("figures.rmse_cm must be finite"));
    compression::SetModel bad_bound = good;
    bad_bound.tucker.error_bound = -0.5;
    CHECK_THROWS_WITH(w.put_model("walks", bad_bound, {}), Catch::Contains("error_bound must be finite and >= 0"));
    CHECK_FALSE(w.view().load_model("walks").has_value());  // nothing was written by the refusals
    w.put_model("walks", good, {});
    CHECK(w.view().load_model("walks").has_value());
}

TEST_CASE("model: malformed stored models give a StoreError naming the dataset", "[store][model][bad]") {
    {
        const auto file = test_data_dir() / "bad-model-shape.h5";
        const auto [path, what] = load_error(file);
        CHECK(path == "/sets/tiny_set/model/dof_basis");
        CHECK_THAT(what, Catch::Contains("bad-model-shape.h5: /sets/tiny_set/model/dof_basis: expected shape (9, 1)"));
        CHECK_THAT(what, Catch::Contains("found (8, 1)"));
        const ValidationReport r = validate_database(file);
        INFO(all_violations(r));
        CHECK(has_violation(r, "/sets/tiny_set/model/dof_basis", "axis 0 ('dof'): expected 9 (D as in"));
        // The listing still works (it reads shapes only).
        CHECK(Database(file).sets()[0].model_ranks == std::array<std::size_t, 3>{1, 2, 2});
    }
    {
        const auto file = test_data_dir() / "bad-model-rank.h5";
        const auto [path, what] = load_error(file);
        CHECK(path == "/sets/tiny_set/model/core");
        CHECK_THAT(what, Catch::Contains("expected 1 <= R3 <= N = 2"));
        const ValidationReport r = validate_database(file);
        INFO(all_violations(r));
        CHECK(has_violation(r, "/sets/tiny_set/model/core", "expected 1 <= R3 <= N = 2"));
    }
    {
        const auto file = test_data_dir() / "bad-model-nan.h5";
        const auto [path, what] = load_error(file);
        CHECK(path == "/sets/tiny_set/model/time_basis");
        CHECK_THAT(what, Catch::Contains("expected finite values, found nan at element 2"));
        const ValidationReport r = validate_database(file);
        INFO(all_violations(r));
        CHECK(has_violation(r, "/sets/tiny_set/model/time_basis", "expected finite values"));
    }
    {
        const auto file = test_data_dir() / "bad-model-orphan.h5";
        const auto [path, what] = load_error(file);
        CHECK(path == "/sets/tiny_set/model");
        CHECK_THAT(what, Catch::Contains("a model requires the aligned tensor it describes, but "
                                         "/sets/tiny_set/aligned does not exist"));
        const ValidationReport r = validate_database(file);
        INFO(all_violations(r));
        CHECK(has_violation(r, "/sets/tiny_set/model", "a model requires the aligned tensor"));
        // The root is fine, so a writing session still opens it (and could repair it).
        TempDir dir("model-orphan");
        std::filesystem::copy_file(file, dir / "orphan.h5");
        CHECK_NOTHROW(DatabaseWriter(dir / "orphan.h5"));
    }
}

TEST_CASE("model: mocapdb validate passes the version-2 reference file and reports its version", "[store][model][cli]") {
    const CommandResult ok = run_cli("validate " + quoted((test_data_dir() / "reference-v2.h5").string()));
    INFO(ok.output);
    CHECK(ok.exit_code == 0);
    CHECK(ok.output.find("valid mocapdb format 2 file") != std::string::npos);
    const CommandResult v1 = run_cli("validate " + quoted((test_data_dir() / "reference-v1.h5").string()));
    INFO(v1.output);
    CHECK(v1.exit_code == 0);
    CHECK(v1.output.find("valid mocapdb format 1 file") != std::string::npos);
    const CommandResult bad = run_cli("validate " + quoted((test_data_dir() / "bad-model-rank.h5").string()));
    INFO(bad.output);
    CHECK(bad.exit_code == 1);
    CHECK(bad.output.find("/sets/tiny_set/model/core: ") != std::string::npos);
    CHECK(bad.output.find("not a valid mocapdb format 2 file: 1 violation") != std::string::npos);
}
