// `mocapdb report DB --collection` (issue 14 item 4) on a small database of shared PFNN clips: every
// JSON key, the bound per E, ratios consistent with bytes, the ACL columns against the reference, the
// lossless tier beside gzip -9, output files refused without --force, a bad reference named by file
// and line, option conflicts, and an empty database.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "mini_json.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/store/database.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

TEST_CASE("report --collection: figures per E on shared clips, beside ACL and gzip -9", "[cli][report][shared]") {
    MOCAPDB_REQUIRE_CLI();
    const auto bvh = datasets_dir() / "cmu-walkrun-pfnn";
    const auto acl = reference_dir() / "acl" / "cmu-walkrun-pfnn.csv";
    MOCAPDB_REQUIRE_SHARED(bvh);
    MOCAPDB_REQUIRE_SHARED(acl);
    TempDir dir("report-collection");
    const std::string db = (dir / "db.h5").string();
    const CommandResult imported =
        run_cli("import " + quoted((bvh / "02_01_60fps.bvh").string()) + " " + quoted((bvh / "02_03_60fps.bvh").string()) +
                " " + quoted((bvh / "16_39_60fps.bvh").string()) + " --fps 60 -o " + quoted(db));
    INFO(imported.output);
    REQUIRE(imported.exit_code == 0);

    const std::string csv = (dir / "r.csv").string(), svg = (dir / "r.svg").string();
    const CommandResult r = run_cli("report " + quoted(db) + " --collection --max-error-cm 1,0.1 --poses 500 --json --reference " +
                                    quoted(acl.string()) + " --source-dir " + quoted(bvh.string()) + " --csv " +
                                    quoted(csv) + " --svg " + quoted(svg));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json j = parse_json(r.out);
    CHECK(j["clips"].number == 3);
    CHECK(j["groups"].number == 1);
    const double float32 = j["float32_bytes"].number;
    CHECK(float32 == j["frames"].number * 132 * 4);  // PFNN: 132 channels
    REQUIRE(j["targets"].items.size() == 2);
    const double E[] = {1.0, 0.1};
    double previous_bytes = 0.0;
    for (std::size_t t = 0; t < 2; ++t) {
        const Json& row = j["targets"][t];
        INFO("E = " << E[t]);
        CHECK(row["max_error_cm"].number == E[t]);
        for (const char* key : {"bytes", "float32_bytes", "ratio_float32", "bytes_per_second", "bits_per_joint_frame",
                                "max_cm", "p99_cm", "rmse_cm", "encode_seconds", "stream_mb_per_second",
                                "decode_pose_us", "resident_bytes", "indexed_local_pose_us", "index_bytes", "poses_timed", "clips", "frames", "motion_seconds", "raw_windows",
                                "pack_attempts", "acl", "group_figures"})
            CHECK(row.has(key));
        const double bytes = row["bytes"].number;
        CHECK(bytes > 0);
        CHECK(bytes > previous_bytes);  // a tighter bound costs more
        previous_bytes = bytes;
        CHECK(row["max_cm"].number <= E[t]);
        CHECK(row["max_cm"].number > 0.0);
        CHECK(row["p99_cm"].number <= row["max_cm"].number);
        CHECK(row["rmse_cm"].number <= row["max_cm"].number);
        CHECK(row["float32_bytes"].number == float32);
        CHECK(row["ratio_float32"].number == Approx(float32 / bytes));
        CHECK(row["bytes_per_second"].number == Approx(bytes / j["motion_seconds"].number));
        CHECK(row["bits_per_joint_frame"].number == Approx(8.0 * bytes / (j["frames"].number * 57)));  // 43 joints + 14 end sites
        CHECK(row["decode_pose_us"].number > 0.0);
        CHECK(row["resident_bytes"].number > 0.0);
        CHECK(row["indexed_local_pose_us"].number > 0.0);
        CHECK(row["index_bytes"].number == 0.0);  // runtime groups (the default) need no index
        CHECK(row["poses_timed"].number == 500);
        CHECK(row["stream_mb_per_second"].number > 0.0);
        REQUIRE(row["group_figures"].items.size() == 1);
        CHECK(row["group_figures"][0]["bytes"].number == bytes);
        const Json& a = row["acl"];
        REQUIRE(a.kind == Json::Object);
        // Our max is within ACL's measured range at both E here (0.0102 to 1.82 cm over these clips).
        REQUIRE(a["bytes_at_max"].kind == Json::Number);
        CHECK(a["smaller_at_max"].number == Approx(a["bytes_at_max"].number / bytes));
        CHECK(a["smaller_at_max"].number > 1.0);
        if (a["bytes_at_rmse"].kind == Json::Number) {
            CHECK(a["smaller_at_rmse"].number == Approx(a["bytes_at_rmse"].number / bytes));
        } else {
            // Our RMSE above ACL's coarsest setting's on these clips: no ACL bytes at it, none invented.
            double acl_rmse = 0.0;
            for (const Json& setting : j["reference"]["settings"].items)
                acl_rmse = std::max(acl_rmse, setting["rmse_cm"].number);
            CHECK(row["rmse_cm"].number > acl_rmse);
            CHECK(a["smaller_at_rmse"].kind == Json::Null);
        }
    }
    const Json& ref = j["reference"];
    CHECK(ref["comparable"].boolean);
    CHECK(ref["clips_missing"].items.empty());
    REQUIRE(ref["settings"].items.size() == 4);
    for (const Json& s : ref["settings"].items) CHECK(s["clips"].number == 3);
    const Json& l = j["lossless"];
    CHECK(l["bytes"].number > 0);
    CHECK(l["ratio_float32"].number == Approx(float32 / l["bytes"].number));
    REQUIRE(l["gzip9_available"].boolean);
    CHECK(l["sources_found"].number == 3);
    const double gzip = l["gzip9_bytes"].number;
    CHECK(gzip > l["bytes"].number);  // the lossless tier beats gzip -9 of the text
    CHECK(gzip < l["source_text_bytes"].number);
    CHECK(l["gzip9_ratio_float32"].number == Approx(float32 / gzip));

    // CSV: a header, one row per E and the lossless row; SVG: ours, ACL and the flat exact tiers.
    const std::string csv_text = read_text_file(csv);
    CHECK(csv_text.rfind("tier,max_error_cm,bytes,", 0) == 0);
    CHECK(std::count(csv_text.begin(), csv_text.end(), '\n') == 4);
    CHECK(csv_text.find("\nlossless,0,") != std::string::npos);
    {  // every row has the header's cells
        std::istringstream lines(csv_text);
        std::string header, row;
        std::getline(lines, header);
        while (std::getline(lines, row)) CHECK(std::count(row.begin(), row.end(), ',') == std::count(header.begin(), header.end(), ','));
    }
    const std::string svg_text = read_text_file(svg);
    CHECK(svg_text.find("<svg") == 0);
    CHECK(svg_text.find("packed tier (ours)") != std::string::npos);
    CHECK(svg_text.find("ACL (reference table)") != std::string::npos);
    CHECK(svg_text.find("gzip -9 source text") != std::string::npos);

    // Existing output files are refused before any work; --force overwrites them.
    for (const std::string& option : {"--csv " + quoted(csv), "--svg " + quoted(svg)}) {
        const CommandResult refused = run_cli("report " + quoted(db) + " --collection --max-error-cm 1 " + option);
        CHECK(refused.exit_code == 1);
        CHECK(refused.err.find("exists (pass --force to overwrite it)") != std::string::npos);
    }
    const CommandResult forced = run_cli("report " + quoted(db) + " --collection --max-error-cm 1 --poses 100 --force --csv " + quoted(csv));
    INFO(forced.output);
    CHECK(forced.exit_code == 0);

    // The text table: the columns and the lossless line; without --source-dir gzip is "not available".
    CHECK(forced.out.find("ACL B @max") != std::string::npos);
    CHECK(forced.out.find("x smaller") != std::string::npos);
    CHECK(forced.out.find("lossless tier:") != std::string::npos);
    CHECK(forced.out.find("gzip -9 of the source text: not available (no source folder given") != std::string::npos);
    CHECK(forced.out.find("n/a") != std::string::npos);  // no --reference: no ACL figures

    // A changed source file is not guessed at: gzip is not available and the reason names it.
    const auto sources = dir / "sources";
    std::filesystem::create_directories(sources);
    for (const char* f : {"02_01_60fps.bvh", "02_03_60fps.bvh", "16_39_60fps.bvh"})
        std::filesystem::copy_file(bvh / f, sources / f);
    std::ofstream(sources / "16_39_60fps.bvh", std::ios::app) << "\n";
    const CommandResult changed = run_cli("report " + quoted(db) + " --collection --max-error-cm 1 --poses 10 --json --source-dir " +
                                          quoted(sources.string()));
    INFO(changed.output);
    REQUIRE(changed.exit_code == 0);
    const Json cj = parse_json(changed.out);
    CHECK_FALSE(cj["lossless"]["gzip9_available"].boolean);
    CHECK(cj["lossless"]["gzip9_bytes"].kind == Json::Null);
    CHECK(cj["lossless"]["sources_changed"].number == 1);
    CHECK(cj["lossless"]["gzip9_unavailable_reason"].text.find("16_39_60fps.bvh") != std::string::npos);

    // A bad reference table: one line naming the file and line, before any packing.
    const auto bad = dir / "bad.csv";
    {
        std::ofstream out(bad);
        const std::string table = read_text_file(acl);
        out << table.substr(0, table.find('\n') + 1) << "cmu-walkrun-pfnn,02_01_60fps,0.1,ok,43,14\n";
    }
    const CommandResult refused = run_cli("report " + quoted(db) + " --collection --reference " + quoted(bad.string()));
    CHECK(refused.exit_code == 1);
    CHECK(refused.err.find(bad.string() + ":2:") != std::string::npos);
    CHECK(refused.err.find("expected 22 comma-separated cells") != std::string::npos);
    CHECK(std::count(refused.err.begin(), refused.err.end(), '\n') == 1);

    // A reference without these clips: no comparison, said so.
    const CommandResult other = run_cli("report " + quoted(db) + " --collection --max-error-cm 1 --poses 10 --json --reference " +
                                        quoted((reference_dir() / "acl" / "cmu-asfamc.csv").string()));
    INFO(other.output);
    REQUIRE(other.exit_code == 0);
    const Json oj = parse_json(other.out);
    CHECK_FALSE(oj["reference"]["comparable"].boolean);
    CHECK(oj["reference"]["clips_missing"].items.size() == 3);
    CHECK(oj["targets"][0]["acl"].kind == Json::Null);

    // --set and --collection exclude each other; one is required; set options do not mix in.
    CHECK(run_cli("report " + quoted(db) + " --collection --set walks").exit_code != 0);
    const CommandResult neither = run_cli("report " + quoted(db));
    CHECK(neither.exit_code != 0);
    CHECK(neither.output.find("--collection") != std::string::npos);
    CHECK(run_cli("report " + quoted(db) + " --collection --sweep").exit_code != 0);
    CHECK(run_cli("report " + quoted(db) + " --set walks --max-error-cm 1").exit_code != 0);
}

TEST_CASE("report --collection: an empty database gives an empty report, not a crash", "[cli][report]") {
    MOCAPDB_REQUIRE_CLI();
    TempDir dir("report-empty");
    const auto db = dir / "empty.h5";
    {
        DatabaseWriter w(db);
        w.commit();
    }
    const CommandResult j = run_cli("report " + quoted(db.string()) + " --collection --json");
    INFO(j.output);
    REQUIRE(j.exit_code == 0);
    const Json r = parse_json(j.out);
    CHECK(r["clips"].number == 0);
    REQUIRE(r["targets"].items.size() == 5);  // 1, 0.5, 0.1, 0.03, 0.01 by default
    const double defaults[] = {1, 0.5, 0.1, 0.03, 0.01};
    for (std::size_t t = 0; t < 5; ++t) CHECK(r["targets"][t]["max_error_cm"].number == defaults[t]);
    for (const Json& t : r["targets"].items) {
        CHECK(t["bytes"].number == 0);
        CHECK(t["group_figures"].items.empty());
    }
    const CommandResult text = run_cli("report " + quoted(db.string()) + " --collection");
    INFO(text.output);
    CHECK(text.exit_code == 0);
    CHECK(text.out.find("the database has no clips") != std::string::npos);
    const auto acl = reference_dir() / "acl" / "cmu-asfamc.csv";
    if (std::filesystem::exists(acl)) {
        const CommandResult ref = run_cli("report " + quoted(db.string()) + " --collection --json --reference " + quoted(acl.string()));
        INFO(ref.output);
        CHECK(ref.exit_code == 0);
        CHECK_FALSE(parse_json(ref.out)["reference"]["comparable"].boolean);
    }
}

TEST_CASE("report --collection: rows at 0.03 and 0.01 cm beside ACL, parts per target, honest lossless bytes, "
          "source files in subfolders", "[cli][report][shared]") {
    MOCAPDB_REQUIRE_CLI();
    const auto bvh = datasets_dir() / "cmu-walkrun-pfnn";
    const auto acl = reference_dir() / "acl" / "cmu-walkrun-pfnn.csv";
    MOCAPDB_REQUIRE_SHARED(bvh);
    MOCAPDB_REQUIRE_SHARED(acl);
    TempDir dir("report-fine");
    // The source files two folders down: --source-dir searches subfolders.
    const auto nested = dir / "sources" / "walks" / "60fps";
    std::filesystem::create_directories(nested);
    // Two clips whose ACL error at its most precise setting is above 0.01 cm (0.0112 and 0.0113).
    for (const char* name : {"45_01_60fps.bvh", "83_37_60fps.bvh"}) std::filesystem::copy_file(bvh / name, nested / name);
    const std::string db = (dir / "db.h5").string();
    const CommandResult imported = run_cli("import " + quoted(nested.string()) + " --fps 60 -o " + quoted(db));
    INFO(imported.output);
    REQUIRE(imported.exit_code == 0);

    const CommandResult r = run_cli("report " + quoted(db) + " --collection --max-error-cm 0.03,0.01 --poses 100 --json --reference " +
                                    quoted(acl.string()) + " --source-dir " + quoted((dir / "sources").string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json j = parse_json(r.out);
    REQUIRE(j["reference"]["comparable"].boolean);
    // ACL's most precise setting (0.01 cm, its default) over these clips.
    double acl_finest_bytes = 0.0, acl_finest_max = 0.0;
    for (const Json& setting : j["reference"]["settings"].items)
        if (setting["precision_cm"].number == 0.01) {
            acl_finest_bytes = setting["bytes"].number;
            acl_finest_max = setting["max_cm"].number;
        }
    REQUIRE(acl_finest_bytes > 0.0);
    const double E[] = {0.03, 0.01};
    for (std::size_t t = 0; t < 2; ++t) {
        const Json& row = j["targets"][t];
        INFO("E = " << E[t]);
        CHECK(row["max_error_cm"].number == E[t]);
        CHECK(row["max_cm"].number <= E[t]);
        double parts = 0.0;
        for (const auto& [name, bytes] : row["parts"].members) parts += bytes.number;
        CHECK(parts == row["bytes"].number);
        for (const Json& g : row["group_figures"].items) {
            double group_parts = 0.0;
            for (const auto& [name, bytes] : g["parts"].members) group_parts += bytes.number;
            CHECK(group_parts == g["bytes"].number);
        }
        // A comparison at every E: interpolated inside ACL's range, ACL's most precise setting as a
        // lower bound below it (our max under ACL's smallest measured max).
        const Json& c = row["acl"];
        REQUIRE(c["bytes_at_max"].kind == Json::Number);
        REQUIRE(c["smaller_at_max"].kind == Json::Number);
        CHECK(c["smaller_at_max"].number == Approx(c["bytes_at_max"].number / row["bytes"].number));
        const bool below = row["max_cm"].number < acl_finest_max;
        CHECK(c["max_lower_bound"].boolean == below);
        if (below) CHECK(c["bytes_at_max"].number == acl_finest_bytes);
        else CHECK(c["bytes_at_max"].number <= acl_finest_bytes);
    }
    CHECK(j["targets"][1]["acl"]["max_lower_bound"].boolean);  // ACL's 0.01 setting reaches 0.0113 cm here

    // Lossless: the file bytes the clips take, more than their channel data, within the files.
    const Json& l = j["lossless"];
    CHECK(l["bytes"].number > l["channel_bytes"].number + 2 * 2000);
    CHECK(l["bytes"].number < static_cast<double>(Database(db).file_size()));
    CHECK(l["ratio_float32"].number == Approx(l["float32_bytes"].number / l["bytes"].number));
    CHECK(l["gzip9_available"].boolean);
    CHECK(l["sources_found"].number == 2);
    const CommandResult text = run_cli("report " + quoted(db) + " --collection --max-error-cm 0.01 --poses 10 --reference " +
                                       quoted(acl.string()));
    INFO(text.output);
    CHECK(text.exit_code == 0);
    CHECK(text.out.find(">=") != std::string::npos);
}
