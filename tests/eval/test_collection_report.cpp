// The whole-collection report (eval/collection_report.hpp, issue 14 item 4) measures what `pack`
// stores: the same bytes and errors per E; the figures are consistent with each other; an empty
// database gives an empty report; bad options are refused.
#include <catch2/catch.hpp>

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/eval/collection_report.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "store_test_support.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

TEST_CASE("collection report: per E the bytes and errors that pack stores", "[store][report]") {
    TempDir dir("collection-report");
    const auto path = dir / "db.h5";
    {
        DatabaseWriter w(path);
        w.add_clip(synthetic_clip(180, 6, 1), synthetic_source("a.bvh", "report a"));
        w.add_clip(synthetic_clip(75, 6, 2), synthetic_source("b.bvh", "report b"));
        w.add_clip(synthetic_clip(120, 4, 3, 60.0), synthetic_source("c.bvh", "report c"));  // another group
        w.commit();
    }
    eval::CollectionReportOptions o;
    o.max_error_cm = {0.5, 0.05};
    o.random_poses = 300;
    eval::CollectionReport r;
    {
        const Database db(path);
        std::uint64_t last = 0, total = 0;
        bool monotone = true;
        r = eval::collection_report(db, o, [&](const Progress& p) {
            monotone = monotone && p.done >= last;
            last = p.done;
            total = p.total;
        });
        CHECK(monotone);
        CHECK(total == 375 * 2);
        CHECK(last == total);
    }
    CHECK(r.clips == 3);
    CHECK(r.frames == 375);
    CHECK(r.groups == 2);
    REQUIRE(r.targets.size() == 2);
    CHECK(r.clip_names == std::vector<std::string>{"a", "b", "c"});
    for (std::size_t t = 0; t < 2; ++t) {
        const eval::TargetFigures& tf = r.targets[t];
        INFO("E = " << tf.max_error_cm);
        CHECK(tf.max_error_cm == o.max_error_cm[t]);
        CHECK(tf.total.max_cm <= tf.max_error_cm);
        CHECK(tf.total.bytes > 0);
        CHECK(tf.total.ratio_float32() == Approx(static_cast<double>(r.float32_bytes) / static_cast<double>(tf.total.bytes)));
        CHECK(tf.poses_timed == 300);
        REQUIRE(tf.groups.size() == 2);
        std::uint64_t sum = 0;
        for (const eval::GroupFigures& g : tf.groups) sum += g.figures.bytes;
        CHECK(sum == tf.total.bytes);

        // `pack` at the same E stores the same bytes with the same measured errors.
        workflow::PackDatabaseOptions po;
        po.max_error_cm = tf.max_error_cm;
        po.replace = true;
        const workflow::PackDatabaseOutcome packed = workflow::pack_database(path, po);
        CHECK(packed.tier.bytes == tf.total.bytes);
        CHECK(packed.tier.max_cm == tf.total.max_cm);
        CHECK(packed.tier.rmse_cm == Approx(tf.total.rmse_cm).epsilon(1e-12));
        CHECK(packed.float32_bytes == r.float32_bytes);
    }
    CHECK(r.targets[1].total.bytes > r.targets[0].total.bytes);
    CHECK(r.lossless.bytes > 0);
    CHECK_FALSE(r.lossless.gzip_available);  // no source folder given
    CHECK(r.lossless.gzip_reason.find("no source folder") != std::string::npos);
}

TEST_CASE("collection report: empty database and bad options", "[store][report]") {
    TempDir dir("collection-report-empty");
    const auto path = dir / "empty.h5";
    {
        DatabaseWriter w(path);
        w.commit();
    }
    const Database db(path);
    eval::CollectionReportOptions o;
    o.source_dirs = {dir.path()};
    const eval::CollectionReport r = eval::collection_report(db, o);
    CHECK(r.clips == 0);
    CHECK(r.groups == 0);
    REQUIRE(r.targets.size() == 5);  // 1, 0.5, 0.1, 0.03, 0.01 cm by default
    for (const eval::TargetFigures& t : r.targets) {
        CHECK(t.total.bytes == 0);
        CHECK(t.total.ratio_float32() == 0.0);
        CHECK(t.poses_timed == 0);
    }
    CHECK(r.lossless.gzip_available);  // every one of no clips found
    CHECK(r.lossless.gzip_bytes == 0);

    for (const double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
        eval::CollectionReportOptions b;
        b.max_error_cm = {1.0, bad};
        CHECK_THROWS_AS(eval::collection_report(db, b), InvalidArgument);
    }
    eval::CollectionReportOptions none;
    none.max_error_cm.clear();
    CHECK_THROWS_AS(eval::collection_report(db, none), InvalidArgument);
    eval::CollectionReportOptions threads;
    threads.threads = 0;
    CHECK_THROWS_AS(eval::collection_report(db, threads), InvalidArgument);
}
