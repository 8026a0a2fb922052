// The packed tier in the database file (issue 14 items 2, 3, 5): `mocapdb pack` on shared clips of
// both folders, the bound measured by decoding from the file (FK, every joint, end site and source
// frame, against the lossless tier, which is exact to the source), validate, info, export
// --from-packed, frame ranges, corrupted bytes, refused bounds, empty and one-clip databases.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "mini_json.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "mocapdb/store/storage_extents.hpp"
#include "mocapdb/store/validate.hpp"
#include "fk_error.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

TEST_CASE("packed tier: shared clips of both folders packed at E = 1 and 0.5 through the CLI decode within E",
          "[store][packed][shared]") {
    MOCAPDB_REQUIRE_CLI();
    const auto amc = datasets_dir() / "cmu-asfamc";
    const auto bvh = datasets_dir() / "cmu-walkrun-pfnn";
    MOCAPDB_REQUIRE_SHARED(amc);
    MOCAPDB_REQUIRE_SHARED(bvh);
    TempDir dir("packed-shared");
    const std::string db = (dir / "db.h5").string();
    const CommandResult imported =
        run_cli("import " + quoted((amc / "02_01.amc").string()) + " " + quoted((amc / "16_49.amc").string()) + " " +
                quoted((bvh / "02_03_60fps.bvh").string()) + " " + quoted((bvh / "16_39_60fps.bvh").string()) + " -o " +
                quoted(db));
    INFO(imported.output);
    REQUIRE(imported.exit_code == 0);

    for (const double E : {1.0, 0.5}) {
        INFO("E = " << E);
        const bool again = E != 1.0;
        const CommandResult packed = run_cli("pack " + quoted(db) + " --max-error-cm " + std::to_string(E) + " --json" +
                                             (again ? " --force" : ""));
        INFO(packed.output);
        REQUIRE(packed.exit_code == 0);
        const Json j = parse_json(packed.out);
        CHECK(j["max_error_cm"].number == E);
        CHECK(j["clips"].number == 4);
        CHECK(j["bytes"].number > 0);
        CHECK(j["max_cm"].number <= E);
        CHECK(j["max_cm"].number > 0.0);
        CHECK(j["p99_cm"].number <= j["max_cm"].number);
        CHECK(j["rmse_cm"].number <= j["max_cm"].number);
        CHECK(j["replaced"].boolean == again);
        // Two groups: the ASF rig at 120 Hz, the PFNN rig at its BVH rate.
        REQUIRE(j["groups"].items.size() == 2);
        double group_bytes = 0.0, group_frames = 0.0;
        for (const Json& g : j["groups"].items) {
            CHECK(g["max_cm"].number <= E);
            CHECK(g["clips"].number == 2);
            group_bytes += g["bytes"].number;
            group_frames += g["frames"].number;
        }
        CHECK(group_bytes == j["bytes"].number);
        CHECK(group_frames == j["frames"].number);

        // Decoding every clip from the file: FK max error <= E against the source clip.
        const Database view(db);
        const auto tier = view.packed();
        REQUIRE(tier);
        CHECK(tier->max_error_cm == E);
        CHECK(static_cast<double>(tier->bytes) == j["bytes"].number);
        std::size_t frames = 0;
        for (const ClipRecord& r : view.clips()) {
            INFO(r.id);
            const Clip source = view.load_clip(r.id);  // the lossless tier: exact to the source text
            const Clip decoded = view.load_clip_packed(r.id);
            CHECK(decoded.frame_rate == Approx(source.frame_rate).epsilon(1e-6));
            const double err = max_position_error(source, decoded);
            CHECK(err <= E);
            const auto where = tier->find(r.id);
            REQUIRE(where);
            const PackedClipRecord& c = tier->groups[where->first].clips[where->second];
            CHECK(c.max_cm == Approx(err).margin(1e-9));  // the stored figure is what a reader gets
            CHECK(c.payload_bytes > 0);
            frames += decoded.frame_count();
            // A frame range decodes to the same rows as the whole clip.
            const std::size_t b = decoded.frame_count() / 3, e = std::min(decoded.frame_count(), b + 45);
            const Clip part = view.load_clip_packed(r.id, b, e);
            REQUIRE(part.frame_count() == e - b);
            CHECK((part.channels - decoded.channels.middleRows(static_cast<Eigen::Index>(b),
                                                               static_cast<Eigen::Index>(e - b)))
                      .cwiseAbs()
                      .maxCoeff() == 0.0);
        }
        CHECK(static_cast<double>(frames) == j["frames"].number);
        const ValidationReport report = validate_database(db);
        INFO(all_violations(report));
        CHECK(report.ok());
    }

    // A second pack without --force is refused; the tier stays.
    const CommandResult refused = run_cli("pack " + quoted(db) + " --max-error-cm 1");
    CHECK(refused.exit_code == 1);
    CHECK(refused.err.find("already has a packed tier (max error 0.5 cm)") != std::string::npos);
    CHECK(refused.err.find("--force") != std::string::npos);

    // info: which tiers each clip has, bytes per tier.
    const CommandResult info = run_cli("info " + quoted(db) + " --json");
    INFO(info.output);
    REQUIRE(info.exit_code == 0);
    const Json ij = parse_json(info.out);
    CHECK(ij["packed"]["max_error_cm"].number == 0.5);
    for (const Json& c : ij["clips"].items) {
        CHECK(c["stored_bytes"].number > 0);  // existing key kept
        REQUIRE(c["tiers"].items.size() == 2);
        CHECK(c["tiers"][1].text == "packed");
        CHECK(c["packed_payload_bytes"].number > 0);
        CHECK(c["lossless_bytes"].number == c["stored_bytes"].number);
    }
    const CommandResult text = run_cli("info " + quoted(db));
    CHECK(text.out.find("lossless+packed") != std::string::npos);

    // export --from-packed writes the decoded clip as BVH.
    const std::string out = (dir / "16_49_packed.bvh").string();
    const CommandResult exported = run_cli("export " + quoted(db) + " --clip 16_49 --from-packed -o " + quoted(out));
    INFO(exported.output);
    REQUIRE(exported.exit_code == 0);
    CHECK(exported.out.find("decoded from the packed tier") != std::string::npos);
    const Clip reread = read_clip(out);
    const Database view(db);
    CHECK(reread.frame_count() == view.find_clip("16_49")->frames);
    // 9 significant digits in the text: the bound holds up to that rounding.
    CHECK(max_position_error(view.load_clip("16_49"), reread) <= 0.5 + 1e-3);
}

TEST_CASE("packed tier: a corrupted packed dataset gives a checksum error naming it", "[store][packed][bad]") {
    TempDir dir("packed-corrupt");
    const auto file = dir / "db.h5";
    {
        DatabaseWriter w(file);
        w.add_clip(synthetic_clip(3000, 6, 3), synthetic_source("walk.bvh", "packed corrupt"));
        w.add_clip(synthetic_clip(200, 6, 4), synthetic_source("other.bvh", "packed other"));
        w.commit();
    }
    workflow::PackDatabaseOptions o;
    o.max_error_cm = 0.5;
    const workflow::PackDatabaseOutcome outcome = workflow::pack_database(file, o);
    REQUIRE(outcome.tier.groups.size() == 1);
    CHECK(outcome.tier.max_cm <= 0.5);
    REQUIRE(validate_database(file).ok());
    const std::string path = "/packed/g0/bytes";
    const auto extents = dataset_extents(file, path);
    REQUIRE(!extents.empty());
    INFO("chunk of " << extents.front().size << " bytes, group of " << outcome.tier.bytes << " bytes");
    REQUIRE(extents.front().size > 64);
    flip_bytes(extents.front().file, extents.front().offset + extents.front().size / 2, 4);

    const Database db(file);
    CHECK_NOTHROW(db.load_clip("walk"));  // the lossless tier is intact
    CHECK_THROWS_AS(db.load_clip_packed("walk"), ChecksumError);
    CHECK_THROWS_WITH(db.load_clip_packed("walk"),
                      Catch::Contains("db.h5: /packed/g0/bytes: checksum mismatch in dataset /packed/g0/bytes"));
    const ValidationReport r = validate_database(file);
    INFO(all_violations(r));
    CHECK_FALSE(r.ok());
    CHECK(has_violation(r, path, "checksum mismatch in dataset /packed/g0/bytes"));
    if (!cli_path().empty()) {
        const CommandResult cli = run_cli("validate " + quoted(file.string()));
        INFO(cli.output);
        CHECK(cli.exit_code == 1);
        CHECK(cli.output.find("/packed/g0/bytes: ") != std::string::npos);
        CHECK(cli.output.find("checksum mismatch") != std::string::npos);
    }
}

TEST_CASE("packed tier: E <= 0 or NaN refused, empty and one-clip databases pack", "[store][packed]") {
    TempDir dir("packed-edges");
    const auto empty = dir / "empty.h5";
    {
        DatabaseWriter w(empty);
        w.commit();
    }
    for (const double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
        workflow::PackDatabaseOptions o;
        o.max_error_cm = bad;
        CHECK_THROWS_AS(workflow::pack_database(empty, o), InvalidArgument);
    }
    CHECK_FALSE(Database(empty).packed());  // nothing was written
    if (!cli_path().empty()) {
        for (const char* bad : {"0", "nan", "-0.5"}) {
            INFO(bad);
            const CommandResult r = run_cli("pack " + quoted(empty.string()) + " --max-error-cm " + bad);
            CHECK(r.exit_code == 1);
            CHECK(r.err.find("max error must be a finite number > 0") != std::string::npos);
        }
        // The empty database packs to an empty tier.
        const CommandResult r = run_cli("pack " + quoted(empty.string()) + " --max-error-cm 1 --json");
        INFO(r.output);
        REQUIRE(r.exit_code == 0);
        const Json j = parse_json(r.out);
        CHECK(j["clips"].number == 0);
        CHECK(j["frames"].number == 0);
        CHECK(j["bytes"].number == 0);
        CHECK(j["groups"].items.empty());
    } else {
        workflow::PackDatabaseOptions o;
        workflow::pack_database(empty, o);
    }
    const auto tier = Database(empty).packed();
    REQUIRE(tier);
    CHECK(tier->groups.empty());
    const ValidationReport er = validate_database(empty);
    INFO(all_violations(er));
    CHECK(er.ok());

    // One clip.
    const auto one = dir / "one.h5";
    const Clip clip = synthetic_clip(150, 5, 9);
    {
        DatabaseWriter w(one);
        w.add_clip(clip, synthetic_source("solo.bvh", "packed solo"));
        w.commit();
    }
    workflow::PackDatabaseOptions o;
    o.max_error_cm = 0.25;
    const workflow::PackDatabaseOutcome outcome = workflow::pack_database(one, o);
    CHECK(outcome.tier.clips == 1);
    CHECK(outcome.tier.frames == 150);
    CHECK(outcome.tier.max_cm <= 0.25);
    const Database db(one);
    CHECK(max_position_error(db.load_clip("solo"), db.load_clip_packed("solo")) <= 0.25);
    CHECK_THROWS_AS(db.load_clip_packed("solo", 150), InvalidArgument);
    CHECK_THROWS_AS(db.load_clip_packed("nobody"), StoreError);
    const ValidationReport r = validate_database(one);
    INFO(all_violations(r));
    CHECK(r.ok());
}
