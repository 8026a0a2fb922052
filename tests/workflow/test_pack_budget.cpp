// `mocapdb pack --max-bytes N` and the byte accounting of pack (issue 36 items 4 and 5): the tier
// stored within the budget at the smallest E found, the E reported; a budget no E meets refused
// naming the smallest size, leaving the file as it was; --max-bytes and --max-error-cm exclusive;
// `parts` summing exactly to the bytes in total and per group; no group of one clip when a rig's
// clips are split into several groups.
#include <catch2/catch.hpp>

#include "mini_json.hpp"
#include "mocapdb/packing/byte_parts.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

std::filesystem::path small_database(const TempDir& dir) {
    const auto db = dir / "db.h5";
    DatabaseWriter w(db);
    for (unsigned k = 0; k < 4; ++k)
        w.add_clip(synthetic_clip(300, 6, 20 + k), synthetic_source("c" + std::to_string(k) + ".bvh", "budget " + std::to_string(k)));
    w.commit();
    return db;
}

double sum_of(const Json& parts) {
    double sum = 0.0;
    for (const auto& [name, bytes] : parts.members) sum += bytes.number;
    return sum;
}

}  // namespace

TEST_CASE("pack --max-bytes: the smallest E whose bytes fit, within the budget, and the E reached", "[store][packed][cli]") {
    MOCAPDB_REQUIRE_CLI();
    TempDir dir("pack-budget");
    const auto db = small_database(dir);
    workflow::PackDatabaseOptions o;
    o.max_error_cm = 1.0;
    const std::uint64_t coarse = workflow::pack_database(db, o).tier.bytes;
    o.max_error_cm = 0.1;
    o.replace = true;
    const std::uint64_t fine = workflow::pack_database(db, o).tier.bytes;
    REQUIRE(fine > coarse);
    const std::uint64_t budget = (coarse + fine) / 2;

    const CommandResult r = run_cli("pack " + quoted(db.string()) + " --max-bytes " + std::to_string(budget) + " --force --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json j = parse_json(r.out);
    const double E = j["max_error_cm"].number;
    CHECK(j["bytes"].number <= static_cast<double>(budget));
    CHECK(E > 0.1);
    CHECK(E < 1.0);
    CHECK(j["max_cm"].number <= E);
    CHECK(j["budget"]["max_bytes"].number == static_cast<double>(budget));
    CHECK(j["budget"]["max_error_cm"].number == E);
    // Every E tried below the one chosen missed the budget, the closest by at most about 2 %: E is
    // the smallest that fits, to the search's resolution.
    double closest_miss = 0.0;
    bool chosen_tried = false;
    for (const Json& t : j["budget"]["tried"].items) {
        CHECK(t["fits"].boolean == (t["bytes"].number <= static_cast<double>(budget)));
        if (t["max_error_cm"].number < E) {
            CHECK_FALSE(t["fits"].boolean);
            closest_miss = std::max(closest_miss, t["max_error_cm"].number);
        }
        if (t["max_error_cm"].number == E) chosen_tried = t["fits"].boolean && t["bytes"].number == j["bytes"].number;
    }
    CHECK(chosen_tried);
    REQUIRE(closest_miss > 0.0);
    CHECK(E / closest_miss <= 1.03);
    CHECK(sum_of(j["parts"]) == j["bytes"].number);
    // What is stored is what was reported.
    const auto tier = Database(db).packed();
    REQUIRE(tier);
    CHECK(tier->max_error_cm == E);
    CHECK(static_cast<double>(tier->bytes) == j["bytes"].number);
    const CommandResult text = run_cli("pack " + quoted(db.string()) + " --max-bytes " + std::to_string(budget) + " --force");
    CHECK(text.exit_code == 0);
    CHECK_THAT(text.out, Contains("the smallest max error that fits is") && Contains("bytes by part: header"));

    // A budget no E meets: refused, the smallest reachable size named, the stored tier kept.
    const CommandResult tiny = run_cli("pack " + quoted(db.string()) + " --max-bytes 10 --force");
    CHECK(tiny.exit_code == 1);
    CHECK_THAT(tiny.err, Contains("over the budget of 10 bytes") && Contains("smallest this collection packs to"));
    CHECK(Database(db).packed()->max_error_cm == E);
    workflow::PackDatabaseOptions b;
    b.max_bytes = 10;
    b.replace = true;
    CHECK_THROWS_AS(workflow::pack_database(db, b), workflow::BudgetUnreachable);

    // The two ways to say what to pack exclude each other; a budget of 0 is refused.
    const CommandResult both = run_cli("pack " + quoted(db.string()) + " --max-bytes 5000 --max-error-cm 1 --force");
    CHECK(both.exit_code != 0);
    CHECK_THAT(both.output, Contains("excludes"));
    CHECK(run_cli("pack " + quoted(db.string()) + " --max-bytes 0 --force").exit_code != 0);
}

TEST_CASE("pack: parts sum to the bytes in total and per group, no group of one clip", "[store][packed]") {
    TempDir dir("pack-parts");
    const auto db = small_database(dir);
    workflow::PackDatabaseOptions o;
    o.max_error_cm = 0.5;
    o.max_group_frames = 400;  // 4 clips of 300 frames: runs of one clip, merged into pairs
    const workflow::PackDatabaseOutcome out = workflow::pack_database(db, o);
    REQUIRE(out.tier.groups.size() == 2);
    REQUIRE(out.group_parts.size() == 2);
    for (std::size_t g = 0; g < 2; ++g) {
        CHECK(out.tier.groups[g].clips.size() == 2);
        CHECK(packing::total_bytes(out.group_parts[g]) == out.tier.groups[g].bytes);
    }
    CHECK(packing::total_bytes(out.parts) == out.tier.bytes);
    if (!cli_path().empty()) {
        const CommandResult r = run_cli("pack " + quoted(db.string()) + " --max-error-cm 0.5 --force --json");
        INFO(r.output);
        REQUIRE(r.exit_code == 0);
        const Json j = parse_json(r.out);
        CHECK(sum_of(j["parts"]) == j["bytes"].number);
        for (const Json& g : j["groups"].items) CHECK(sum_of(g["parts"]) == g["bytes"].number);
    }
}
