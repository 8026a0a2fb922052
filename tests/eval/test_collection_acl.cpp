// The collection report beside ACL in-process (eval/collection_acl.hpp, issue #17): three PFNN clips
// packed at E = 1 cm against their ACL table, and the reasons a table cannot be compared.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/eval/collection_acl.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/clip_import.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;

TEST_CASE("collection beside ACL: comparison per E, or why there is none", "[eval][shared]") {
    const auto bvh = test::datasets_dir() / "cmu-walkrun-pfnn";
    const auto acl_dir = test::reference_dir() / "acl";
    MOCAPDB_REQUIRE_SHARED(bvh);
    MOCAPDB_REQUIRE_SHARED(acl_dir / "cmu-walkrun-pfnn.csv");
    test::TempDir dir("collection-acl");
    const auto db_path = dir / "db.h5";
    workflow::ImportOptions io;
    io.frame_rate = 60.0;
    workflow::import_clips(db_path, {bvh / "02_01_60fps.bvh", bvh / "02_03_60fps.bvh", bvh / "16_39_60fps.bvh"}, io, false);
    eval::CollectionReportOptions options;
    options.max_error_cm = {1.0};
    options.random_poses = 10;
    options.source_dirs = {bvh};
    eval::CollectionReport report;
    {
        const Database db(db_path);
        report = eval::collection_report(db, options);
    }
    REQUIRE(report.clips == 3);
    CHECK(report.lossless_bytes_per_second() == Approx(static_cast<double>(report.lossless.bytes) / report.motion_seconds));
    REQUIRE(report.lossless.gzip_available);
    CHECK(report.lossless.gzip_over_lossless() > 1.0);  // the lossless tier beats gzip -9 of the text

    eval::CollectionAcl none = eval::read_collection_acl({});
    CHECK_FALSE(none.given);
    eval::compare_collection_with_acl(none, report);
    CHECK_FALSE(none.usable());
    CHECK(none.per_target.empty());

    eval::CollectionAcl ref = eval::read_collection_acl({(acl_dir / "cmu-walkrun-pfnn.csv").string()});
    REQUIRE(ref.given);
    eval::compare_collection_with_acl(ref, report);
    INFO(ref.unusable);
    REQUIRE(ref.usable());
    CHECK(ref.acl.requested == 3);
    REQUIRE(ref.per_target.size() == 1);
    const eval::AclComparison& c = ref.per_target[0];
    REQUIRE(c.bytes_at_max.has_value());
    CHECK(*c.smaller_at_max == Approx(*c.bytes_at_max / static_cast<double>(report.targets[0].total.bytes)));

    if (std::filesystem::exists(acl_dir / "cmu-asfamc.csv")) {
        eval::CollectionAcl other = eval::read_collection_acl({(acl_dir / "cmu-asfamc.csv").string()});
        eval::compare_collection_with_acl(other, report);
        CHECK_FALSE(other.usable());
        CHECK(other.unusable.find("clips have no row in the reference") != std::string::npos);
        REQUIRE(other.per_target.size() == 1);
        CHECK_FALSE(other.per_target[0].bytes_at_max.has_value());
    }
    CHECK_THROWS_AS(eval::read_collection_acl({(dir / "missing.csv").string()}), Error);
}
