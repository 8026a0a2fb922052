// Database / DatabaseWriter on synthetic data in real HDF5 files: round trips, deduplication,
// atomic sessions, and refusal of inconsistent sets.
#include <catch2/catch.hpp>

#include <fstream>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/validate.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

std::size_t temp_files_beside(const std::filesystem::path& target) {
    std::size_t n = 0;
    for (const auto& e : std::filesystem::directory_iterator(target.parent_path()))
        if (e.path().filename().string().rfind(target.filename().string() + ".tmp-mocapdb-", 0) == 0) ++n;
    return n;
}

MotionSet two_sample_set(const std::string& clip) {
    MotionSet set;
    set.name = "walks";
    set.samples = {{clip, 0, 20}, {clip, 5, 30}};
    set.parameter_names = {"speed", "turn"};
    set.parameter_units = {"cm/s", "rad"};
    set.parameters = MatX(2, 2);
    set.parameters << 100.0, 0.25, 120.0, -0.5;
    set.parameter_source = "csv:params.csv";
    return set;
}

}  // namespace

TEST_CASE("store: a clip, its skeleton and its provenance round-trip exactly", "[store]") {
    TempDir dir("roundtrip");
    const auto db_path = dir / "db.h5";
    const Clip clip = synthetic_clip(300, 4, 1);
    ClipSource source = synthetic_source("walk_01.bvh", "walk one");
    source.subject = "subject 16";
    source.description = "walk, veer left";
    source.labels = {"walk", "veer"};
    {
        DatabaseWriter w(db_path);
        const AddClipResult r = w.add_clip(clip, source);
        CHECK(r.added);
        CHECK(r.id == "walk_01");
        CHECK(r.message == "added as walk_01");
        // The session reads what it wrote before committing.
        CHECK(w.view().has_clip("walk_01"));
        CHECK_FALSE(std::filesystem::exists(db_path));
        w.commit();
    }
    REQUIRE(std::filesystem::exists(db_path));
    CHECK(temp_files_beside(db_path) == 0);

    const Database db(db_path);
    const auto records = db.clips();
    REQUIRE(records.size() == 1);
    const ClipRecord& rec = records.front();
    CHECK(rec.id == "walk_01");
    CHECK(rec.frames == 300);
    CHECK(rec.channels == clip.skeleton->channel_count());
    CHECK(rec.frame_rate == 30.0);
    CHECK(rec.source.file_name == "walk_01.bvh");
    CHECK(rec.source.sha256 == source.sha256);
    CHECK(rec.source.format == "bvh");
    CHECK(rec.source.subject == "subject 16");
    CHECK(rec.source.description == "walk, veer left");
    CHECK(rec.source.labels == std::vector<std::string>{"walk", "veer"});
    CHECK(rec.stored_bytes > 0);

    const Clip back = db.load_clip("walk_01");
    CHECK(back.skeleton->same_structure(*clip.skeleton, 0.0));
    CHECK(back.skeleton->source_units().cm_per_unit == clip.skeleton->source_units().cm_per_unit);
    CHECK(back.skeleton->source_units().degrees == clip.skeleton->source_units().degrees);
    CHECK(back.skeleton->forward() == clip.skeleton->forward());
    CHECK(back.frame_rate == clip.frame_rate);
    CHECK(back.channels == clip.channels);  // float64: bit-exact

    const ValidationReport report = validate_database(db_path);
    INFO((report.ok() ? std::string() : report.violations.front().path + ": " + report.violations.front().message));
    CHECK(report.ok());
}

TEST_CASE("store: duplicates by sha256 are skipped, ids made unique and skeletons shared", "[store]") {
    TempDir dir("dedup");
    const auto db_path = dir / "db.h5";
    const Clip a = synthetic_clip(50, 3, 1);
    const Clip b = synthetic_clip(60, 3, 2);  // same skeleton structure, other motion
    const Clip c = synthetic_clip(40, 5, 3);  // another skeleton
    {
        DatabaseWriter w(db_path);
        CHECK(w.add_clip(a, synthetic_source("take.bvh", "a")).id == "take");
        const AddClipResult again = w.add_clip(b, synthetic_source("sub/take.bvh", "a"));
        CHECK_FALSE(again.added);
        CHECK(again.message == "skipped: duplicate sha256 of clip take");
        CHECK(w.add_clip(b, synthetic_source("take.bvh", "b")).id == "take-2");
        CHECK(w.add_clip(c, synthetic_source("other.bvh", "c")).id == "other");
        w.commit();
    }
    {
        // Appending in a new session: the index of sources survives.
        DatabaseWriter w(db_path);
        CHECK_FALSE(w.add_clip(a, synthetic_source("again.bvh", "a")).added);
        CHECK(w.add_clip(a, synthetic_source("take.bvh", "d")).id == "take-3");
        w.commit();
    }
    const Database db(db_path);
    CHECK(db.clips().size() == 4);
    CHECK(db.skeletons().size() == 2);
    CHECK(db.find_clip("take")->skeleton == db.find_clip("take-2")->skeleton);
    CHECK(db.find_clip("take")->skeleton != db.find_clip("other")->skeleton);
    // One Skeleton object per skeleton id.
    CHECK(db.load_clip("take").skeleton == db.load_clip("take-3").skeleton);
    CHECK(db.find_sha256(synthetic_source("x", "c").sha256) == std::optional<std::string>("other"));
}

TEST_CASE("store: a session that is not committed leaves the target untouched", "[store]") {
    TempDir dir("abort");
    const auto db_path = dir / "db.h5";
    {
        DatabaseWriter w(db_path);
        w.add_clip(synthetic_clip(20, 2, 1), synthetic_source("a.bvh", "a"));
        w.commit();
    }
    const std::string before = file_bytes(db_path);
    {
        DatabaseWriter w(db_path);
        w.add_clip(synthetic_clip(20, 2, 2), synthetic_source("b.bvh", "b"));
        CHECK(std::filesystem::exists(w.temp_path()));
        CHECK(temp_files_beside(db_path) == 1);
    }  // no commit
    CHECK(temp_files_beside(db_path) == 0);
    CHECK(file_bytes(db_path) == before);
    CHECK(Database(db_path).clips().size() == 1);

    DatabaseWriter w(db_path);
    w.commit();
    CHECK_THROWS_AS(w.add_clip(synthetic_clip(20, 2, 3), synthetic_source("c.bvh", "c")), StoreError);
}

TEST_CASE("store: Mode::Create replaces the target with a new database on commit", "[store]") {
    TempDir dir("create");
    const auto db_path = dir / "db.h5";
    {
        DatabaseWriter w(db_path);
        w.add_clip(synthetic_clip(20, 2, 1), synthetic_source("a.bvh", "a"));
        w.commit();
    }
    {
        DatabaseWriter w(db_path, DatabaseWriter::Mode::Create);
        CHECK(w.view().clips().empty());
        w.commit();
    }
    CHECK(Database(db_path).clips().empty());
}

TEST_CASE("store: motion sets and aligned sets round-trip and the tensor is stored (sample, time, dof)", "[store]") {
    TempDir dir("sets");
    const auto db_path = dir / "db.h5";
    const Clip clip = synthetic_clip(40, 3, 7);
    const std::size_t d = PoseLayout(*clip.skeleton).dof_count();
    const MotionSet set = two_sample_set("walk");
    const AlignedSet aligned = synthetic_aligned(d, 12, set);
    {
        DatabaseWriter w(db_path);
        w.add_clip(clip, synthetic_source("walk.bvh", "w"));
        w.put_set(set, false);
        CHECK_FALSE(w.view().load_aligned("walks").has_value());
        CHECK_FALSE(w.view().load_aligned_timing("walks").has_value());
        w.put_aligned("walks", aligned);
        w.commit();
    }
    const Database db(db_path);
    CHECK(db.set_names() == std::vector<std::string>{"walks"});
    CHECK_THROWS_AS(db.load_aligned_timing("nope"), StoreError);
    const MotionSet back = db.load_set("walks");
    CHECK(back.name == set.name);
    REQUIRE(back.samples.size() == 2);
    CHECK(back.samples[1].clip == "walk");
    CHECK(back.samples[1].begin == 5);
    CHECK(back.samples[1].end == 30);
    CHECK(back.parameter_names == set.parameter_names);
    CHECK(back.parameter_units == set.parameter_units);
    CHECK(back.parameters == set.parameters);
    CHECK(back.parameter_source == set.parameter_source);

    const auto a = db.load_aligned("walks");
    REQUIRE(a.has_value());
    CHECK(a->method == "linear");
    CHECK(a->reference == 0);
    CHECK(a->dofs() == static_cast<Eigen::Index>(d));
    CHECK(a->frames() == 12);
    CHECK(a->samples() == 2);
    const Eigen::Tensor<double, 0> diff = (a->tensor - aligned.tensor).abs().maximum();
    CHECK(diff() == 0.0);
    CHECK(a->warps == aligned.warps);
    CHECK(a->mean == aligned.mean);
    CHECK(a->scale == aligned.scale);
    REQUIRE(a->canonical.size() == 2);
    CHECK(a->canonical[1].translation == aligned.canonical[1].translation);
    CHECK(a->canonical[1].yaw == aligned.canonical[1].yaw);
    // The timing and shape alone (what the compressed synthesis model reads): the same warps and D x T x N.
    const auto timing = db.load_aligned_timing("walks");
    REQUIRE(timing.has_value());
    CHECK(timing->dofs() == static_cast<Eigen::Index>(d));
    CHECK(timing->frames() == 12);
    CHECK(timing->samples() == 2);
    CHECK(timing->warps == aligned.warps);

    const auto records = db.sets();
    REQUIRE(records.size() == 1);
    CHECK(records[0].aligned);
    CHECK(records[0].tensor_shape == std::array<std::size_t, 3>{2, 12, d});

    // One element pinned through the file with an independent reader: h5dump's C-order index
    // [s][t][d] holds tensor(d, t, s) = d + 10 t + 100 s.
    const std::size_t pd = 4, pt = 7, ps = 1;
    const CommandResult dump = run_command("h5dump -d /sets/walks/aligned/tensor -s " + std::to_string(ps) + "," +
                                           std::to_string(pt) + "," + std::to_string(pd) + " -c 1,1,1 " +
                                           quoted(db_path.string()));
    INFO(dump.output);
    REQUIRE(dump.exit_code == 0);
    CHECK(dump.output.find("(" + std::to_string(ps) + "," + std::to_string(pt) + "," + std::to_string(pd) +
                           "): 174") != std::string::npos);

    CHECK(validate_database(db_path).ok());
}

TEST_CASE("store: periodic parameters round-trip, sets without them store no parameter_period", "[store]") {
    TempDir dir("periodic");
    const auto db_path = dir / "db.h5";
    const Clip clip = synthetic_clip(40, 3, 7);
    MotionSet periodic = two_sample_set("walk");
    periodic.name = "bearings";
    set_parameter_period(periodic, "turn", 2.0 * kPi);
    CHECK_THROWS_WITH(set_parameter_period(periodic, "bearing", 360.0), Catch::Contains("no parameter 'bearing'") &&
                                                                           Catch::Contains("speed, turn"));
    CHECK_THROWS_WITH(set_parameter_period(periodic, "turn", -1.0), Catch::Contains("must be finite and > 0"));
    {
        DatabaseWriter w(db_path);
        w.add_clip(clip, synthetic_source("walk.bvh", "w"));
        w.put_set(two_sample_set("walk"), false);
        w.put_set(periodic, false);
        w.commit();
    }
    const Database db(db_path);
    CHECK(db.load_set("walks").parameter_periods.size() == 0);
    const MotionSet back = db.load_set("bearings");
    REQUIRE(back.parameter_periods.size() == 2);
    CHECK(back.parameter_periods(0) == 0.0);
    CHECK(back.parameter_periods(1) == 2.0 * kPi);
    const CommandResult ls = run_command("h5ls " + quoted(db_path.string() + "/sets/walks"));
    CHECK(ls.output.find("parameter_period") == std::string::npos);
    CHECK(validate_database(db_path).ok());
}

TEST_CASE("store: categorical parameter levels round-trip; sets without them store none", "[store]") {
    TempDir dir("levels");
    const auto db_path = dir / "db.h5";
    MotionSet styled = two_sample_set("walk");
    styled.name = "styles";
    styled.parameter_names.push_back("style");
    styled.parameter_units.emplace_back();
    styled.parameters.conservativeResize(2, 3);
    styled.parameters.col(2) << 1.0, 0.0;  // level indices
    styled.parameter_levels = {{}, {}, {"calm", "lively"}};
    {
        DatabaseWriter w(db_path);
        w.add_clip(synthetic_clip(40, 3, 7), synthetic_source("walk.bvh", "w"));
        w.put_set(two_sample_set("walk"), false);
        w.put_set(styled, false);
        MotionSet bad = styled;  // a level index that is none: refused before anything is written
        bad.name = "bad";
        bad.parameters(0, 2) = 2.0;
        CHECK_THROWS_WITH(w.put_set(bad, false), Catch::Contains("not a level index in [0, 2)"));
        w.commit();
    }
    const Database db(db_path);
    CHECK(db.load_set("walks").parameter_levels.empty());
    const MotionSet back = db.load_set("styles");
    CHECK(back.parameter_levels == styled.parameter_levels);
    CHECK(back.parameters == styled.parameters);
    CHECK_FALSE(db.has_set("bad"));
    const CommandResult ls = run_command("h5ls " + quoted(db_path.string() + "/sets/walks"));
    CHECK(ls.output.find("parameter_level") == std::string::npos);
    CHECK(validate_database(db_path).ok());
}

TEST_CASE("store: put_set and put_aligned refuse sets that do not fit the stored clips", "[store]") {
    TempDir dir("badsets");
    const auto db_path = dir / "db.h5";
    DatabaseWriter w(db_path);
    const Clip clip = synthetic_clip(40, 3, 7);
    w.add_clip(clip, synthetic_source("walk.bvh", "w"));
    w.add_clip(synthetic_clip(40, 5, 8), synthetic_source("other.bvh", "o"));

    MotionSet set = two_sample_set("walk");
    set.samples[1].clip = "missing";
    CHECK_THROWS_WITH(w.put_set(set, false), Catch::Contains("names clip 'missing', which is not stored"));
    set = two_sample_set("walk");
    set.samples[1].end = 41;
    CHECK_THROWS_WITH(w.put_set(set, false), Catch::Contains("lies beyond clip 'walk' (40 frames)"));
    set = two_sample_set("walk");
    set.samples[1].clip = "other";
    CHECK_THROWS_WITH(w.put_set(set, false), Catch::Contains("share one skeleton"));
    set = two_sample_set("walk");
    set.name = "a/b";
    CHECK_THROWS_WITH(w.put_set(set, false), Catch::Contains("must not contain '/'"));

    set = two_sample_set("walk");
    w.put_set(set, false);
    CHECK_THROWS_WITH(w.put_set(set, false), Catch::Contains("already exists"));
    const std::size_t d = PoseLayout(*clip.skeleton).dof_count();
    CHECK_THROWS_WITH(w.put_aligned("walks", synthetic_aligned(d + 3, 5, set)), Catch::Contains("pose vectors of"));
    AlignedSet too_far = synthetic_aligned(d, 5, set);
    too_far.warps(4, 0) = 25.0;
    CHECK_THROWS_WITH(w.put_aligned("walks", too_far), Catch::Contains("leave its frames"));
    CHECK_THROWS_WITH(w.put_aligned("nope", synthetic_aligned(d, 5, set)), Catch::Contains("is not stored"));
}

TEST_CASE("store: replacing sets reclaims their space at commit", "[store]") {
    TempDir dir("compact");
    const auto db_path = dir / "db.h5";
    const Clip clip = synthetic_clip(400, 3, 7);
    const std::size_t d = PoseLayout(*clip.skeleton).dof_count();
    MotionSet set = two_sample_set("walk");
    {
        DatabaseWriter w(db_path);
        w.add_clip(clip, synthetic_source("walk.bvh", "w"));
        w.put_set(set, false);
        w.put_aligned("walks", synthetic_aligned(d, 300, set));
        w.commit();
    }
    const auto size_once = database_disk_bytes(db_path);
    for (int k = 0; k < 5; ++k) {
        DatabaseWriter w(db_path);
        w.put_set(set, true);  // drops the aligned form too
        CHECK_FALSE(w.view().load_aligned("walks").has_value());
        w.put_aligned("walks", synthetic_aligned(d, 300, set));
        w.commit();
    }
    // Format 4 (segments): each replacement writes a new segment and the previous set's segment is
    // removed; the first segment keeps the clip and, while it holds more live than dead bytes, the
    // first set's dead bytes. Without reclaiming, five replacements would add five sets.
    INFO("after one write " << size_once << " bytes, after five replacements " << database_disk_bytes(db_path));
    CHECK(database_disk_bytes(db_path) <= 2 * size_once);
    std::size_t segments = 0;
    for (const auto& e : std::filesystem::directory_iterator(db_path.string() + ".d"))
        segments += e.path().extension() == ".h5" ? 1 : 0;
    CHECK(segments <= 2);
    CHECK(validate_database(db_path).ok());
    {
        DatabaseWriter w(db_path);
        w.remove_set("walks");
        CHECK_THROWS_AS(w.remove_set("walks"), StoreError);
        w.commit();
    }
    CHECK(Database(db_path).set_names().empty());
}

TEST_CASE("store: opening what is not a database names the file and says what was expected", "[store]") {
    TempDir dir("open");
    CHECK_THROWS_WITH(Database(dir / "absent.h5"), Catch::Contains("absent.h5: no such file"));
    const auto text = dir / "text.h5";
    { std::ofstream(text) << "not hdf5\n"; }
    CHECK_THROWS_AS(Database(text), StoreError);
    CHECK_THROWS_WITH(Database(text), Catch::Contains("text.h5") && Catch::Contains("cannot open as an HDF5 file"));
    // A writer refuses to append to it (and leaves it alone).
    CHECK_THROWS_AS(DatabaseWriter(text), StoreError);
    CHECK(file_bytes(text) == "not hdf5\n");
    CHECK(std::filesystem::directory_iterator(dir.path()) != std::filesystem::directory_iterator());
}
