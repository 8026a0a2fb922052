// The packed tier as the only copy (issue 14 item 3): `mocapdb pack --drop-lossless` removes the
// lossless channels of the packed clips, the file shrinks, every reader decodes those clips from
// the packed tier within E of the source, and nothing can then remove or replace that tier. Also:
// one topology and rate split into several groups by frame count (bounded packing memory).
#include <catch2/catch.hpp>

#include "mini_json.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/import_files.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "mocapdb/store/validate.hpp"
#include "fk_error.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

TEST_CASE("drop lossless: packed clips are read from the packed tier within E, the file shrinks, the tier stays",
          "[store][packed][shared]") {
    MOCAPDB_REQUIRE_CLI();
    const auto bvh = datasets_dir() / "cmu-walkrun-pfnn";
    MOCAPDB_REQUIRE_SHARED(bvh);
    TempDir dir("drop-lossless");
    const std::string db = (dir / "db.h5").string();
    const std::vector<std::string> files = {"02_03_60fps.bvh", "16_39_60fps.bvh", "16_13_60fps.bvh"};
    REQUIRE(run_cli("import " + quoted((bvh / files[0]).string()) + " " + quoted((bvh / files[1]).string()) +
                    " --fps 60 -o " + quoted(db))
                .exit_code == 0);
    std::vector<Clip> sources;
    for (const char* id : {"02_03_60fps", "16_39_60fps"}) sources.push_back(Database(db).load_clip(id));
    const auto before = database_disk_bytes(db);
    std::uint64_t lossless_bytes = 0;
    for (const ClipRecord& r : Database(db).clips()) lossless_bytes += r.stored_bytes;

    // Nothing to drop against without a packed tier.
    const CommandResult refused = run_cli("pack " + quoted(db) + " --drop-lossless");
    CHECK(refused.exit_code != 0);
    CHECK_THAT(refused.err, Catch::Contains("no packed tier"));

    const double E = 0.5;
    const CommandResult packed = run_cli("pack " + quoted(db) + " --max-error-cm 0.5 --drop-lossless --json");
    INFO(packed.output);
    REQUIRE(packed.exit_code == 0);
    const Json pj = parse_json(packed.out);
    CHECK(pj["dropped_lossless_clips"].number == 2);
    // The lossless bytes left the file; what came in is the packed bytes and their group's
    // metadata (a few kB of HDF5 object headers).
    const auto after = database_disk_bytes(db);
    CHECK(static_cast<double>(after) <= static_cast<double>(before - lossless_bytes) + pj["bytes"].number + 16384.0);
    CHECK(pj["bytes"].number * 3 < static_cast<double>(lossless_bytes));
    CHECK(validate_database(db).ok());

    // A clip imported afterwards keeps its lossless channels and is outside the tier.
    REQUIRE(run_cli("import " + quoted((bvh / files[2]).string()) + " --fps 60 -o " + quoted(db)).exit_code == 0);
    {
        const Database view(db);
        for (std::size_t k = 0; k < sources.size(); ++k) {
            const ClipRecord r = *view.find_clip(sources[k].name);
            CHECK_FALSE(r.lossless);
            CHECK(r.stored_bytes == 0);
            CHECK(r.frames == static_cast<std::size_t>(sources[k].frame_count()));
            const Clip loaded = view.load_clip(r.id);  // decoded from the packed tier
            CHECK(loaded.skeleton == view.load_skeleton(r.skeleton));
            CHECK(max_position_error(sources[k], loaded) <= E + 1e-4);
        }
        CHECK(view.find_clip("16_13_60fps")->lossless);
        // Re-importing a dropped clip's source is still recognized as a duplicate.
        CHECK(view.find_sha256(view.find_clip("02_03_60fps")->source.sha256) == std::optional<std::string>("02_03_60fps"));
    }
    const Json info = parse_json(run_cli("info " + quoted(db) + " --json").out);
    for (const Json& c : info["clips"].items) {
        const bool dropped = c["id"].text != "16_13_60fps";
        REQUIRE(c["tiers"].items.size() == 1);
        CHECK(c["tiers"].items[0].text == (dropped ? "packed" : "lossless"));
    }

    // The tier is the only copy now: neither replaced, removed, nor exported as if lossless.
    const CommandResult replace = run_cli("pack " + quoted(db) + " --max-error-cm 1 --force");
    CHECK(replace.exit_code != 0);
    CHECK_THAT(replace.err, Catch::Contains("only copy of clip '02_03_60fps'"));
    {
        DatabaseWriter w(db);
        CHECK_THROWS_WITH(w.remove_packed(), Catch::Contains("only copy of 2 clips"));
    }
    const std::string out = (dir / "x.bvh").string();
    const CommandResult exported = run_cli("export " + quoted(db) + " --clip 02_03_60fps -o " + quoted(out));
    CHECK(exported.exit_code != 0);
    CHECK_THAT(exported.err, Catch::Contains("--from-packed"));
    CHECK(run_cli("export " + quoted(db) + " --clip 02_03_60fps --from-packed -o " + quoted(out)).exit_code == 0);
    CHECK(max_position_error(sources[0], read_clip(out)) <= E + 1e-2);  // + the BVH text's decimals

    // A set over dropped and lossless clips builds (its clips load through the packed tier).
    const CommandResult set = run_cli("set create " + quoted(db) + " --name walks --clips 02_03_60fps 16_13_60fps --extract speed");
    INFO(set.output);
    CHECK(set.exit_code == 0);
    CHECK(validate_database(db).ok());
}

TEST_CASE("drop lossless: a dropped clip outside /packed is reported by validate", "[store][packed][bad]") {
    TempDir dir("drop-bad");
    const auto db = dir / "db.h5";
    {
        DatabaseWriter w(db, DatabaseWriter::Mode::Create);
        w.add_clip(synthetic_clip(40, 5, 1), synthetic_source("a.bvh", "a"));
        w.add_clip(synthetic_clip(50, 5, 2), synthetic_source("b.bvh", "b"));
        w.commit();
    }
    workflow::PackDatabaseOptions o;
    o.max_error_cm = 1.0;
    o.drop_lossless = true;
    const workflow::PackDatabaseOutcome packed = workflow::pack_database(db, o);
    CHECK(packed.dropped_lossless == 2);
    CHECK(validate_database(db).ok());
    // Damage: the tier removed behind the library's back.
    const CommandResult r = run_command("/usr/bin/python3 -c \"import h5py; f = h5py.File('" + db.string() +
                                        "', 'r+'); del f['packed']; f.close()\"");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);  // python3-h5py is installed by scripts/setup.sh
    const ValidationReport v = validate_database(db);
    CHECK(has_violation(v, "/clips/a", "its motion is lost"));
    CHECK_THROWS_WITH(Database(db).load_clip("a"), Catch::Contains("no packed tier"));
}

TEST_CASE("pack: one topology and rate beyond max_group_frames becomes several groups, each within E",
          "[store][packed][shared]") {
    const auto bvh = datasets_dir() / "cmu-walkrun-pfnn";
    MOCAPDB_REQUIRE_SHARED(bvh);
    TempDir dir("pack-split");
    const auto db = dir / "db.h5";
    {
        DatabaseWriter w(db, DatabaseWriter::Mode::Create);
        workflow::ImportOptions io;
        io.frame_rate = 60.0;
        workflow::import_files(w, {bvh / "02_03_60fps.bvh", bvh / "16_39_60fps.bvh", bvh / "16_13_60fps.bvh",
                         bvh / "16_15_60fps.bvh"},
                     io);
        w.commit();
    }
    std::size_t frames = 0;
    for (const ClipRecord& r : Database(db).clips()) frames += r.frames;
    workflow::PackDatabaseOptions o;
    o.max_error_cm = 1.0;
    o.max_group_frames = frames / 2;  // about half: two or three groups of whole clips
    const workflow::PackDatabaseOutcome out = workflow::pack_database(db, o);
    REQUIRE(out.tier.groups.size() >= 2);
    std::size_t packed_frames = 0, clips = 0;
    for (const PackedGroupRecord& g : out.tier.groups) {
        CHECK(g.frame_rate == 60.0);
        // Within the budget, or grown by a one-clip run merged into it: never a group of one clip.
        CHECK(g.clips.size() >= 2);
        CHECK(g.max_cm <= 1.0);
        packed_frames += g.frames;
        clips += g.clips.size();
    }
    CHECK(packed_frames == frames);
    CHECK(clips == 4);
    CHECK(validate_database(db).ok());
    const Database view(db);
    for (const ClipRecord& r : view.clips()) CHECK(max_position_error(view.load_clip(r.id), view.load_clip_packed(r.id)) <= 1.0);
    o.max_group_frames = 0;
    o.replace = true;
    CHECK_THROWS_AS(workflow::pack_database(db, o), InvalidArgument);
}
