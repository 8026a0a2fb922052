// Databases with more clips than HDF5 keeps in a group's compact link storage (8): the clip listing
// (one link iteration, one attribute read per clip group) returns every clip once, sorted, with the
// record find_clip gives; a later session still finds duplicates by source hash; a damaged clip
// attribute is named with its path.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <set>

#include "mocapdb/core/error.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/validate.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

std::string clip_name(int k) { return "walk_" + std::to_string(1000 + 7 * k) + (k % 3 == 0 ? "_l" : "_r"); }

}  // namespace

TEST_CASE("store: listing 40 clips returns each once, sorted, as find_clip", "[store]") {
    TempDir dir("many_clips");
    const auto db_path = dir / "db.h5";
    std::set<std::string> expected;
    {
        DatabaseWriter w(db_path);
        for (int k = 0; k < 40; ++k) {
            ClipSource s = synthetic_source(clip_name(k) + ".bvh", "clip " + std::to_string(k));
            if (k % 5 == 0) s.labels = {"walk", "k" + std::to_string(k)};
            if (k % 4 == 0) s.subject = "subject " + std::to_string(k);
            const AddClipResult r = w.add_clip(synthetic_clip(10 + static_cast<std::size_t>(k), 2, static_cast<unsigned>(k)), s);
            REQUIRE(r.added);
            expected.insert(r.id);
        }
        w.commit();
    }
    const Database db(db_path);
    const std::vector<ClipRecord> records = db.clips();
    REQUIRE(records.size() == 40);
    std::vector<std::string> ids;
    for (const ClipRecord& r : records) ids.push_back(r.id);
    CHECK(std::is_sorted(ids.begin(), ids.end()));
    CHECK(std::set<std::string>(ids.begin(), ids.end()) == expected);
    for (const ClipRecord& r : records) {
        INFO(r.id);
        const auto one = db.find_clip(r.id);
        REQUIRE(one);
        CHECK(one->frames == r.frames);
        CHECK(one->channels == r.channels);
        CHECK(one->frame_rate == r.frame_rate);
        CHECK(one->stored_bytes == r.stored_bytes);
        CHECK(one->source.sha256 == r.source.sha256);
        CHECK(one->source.labels == r.source.labels);
        CHECK(one->source.subject == r.source.subject);
        CHECK(static_cast<Eigen::Index>(r.frames) == db.load_clip(r.id).channels.rows());
        const int k = std::atoi(r.id.substr(5, 4).c_str()) - 1000;
        CHECK(r.frames == static_cast<std::size_t>(10 + k / 7));
    }

    // A new session finds a duplicate among 40 by its hash and adds a new clip under a free id.
    {
        DatabaseWriter w(db_path);
        const AddClipResult again = w.add_clip(synthetic_clip(5, 2, 99), synthetic_source("x.bvh", "clip 17"));
        CHECK_FALSE(again.added);
        CHECK(again.id == clip_name(17));
        CHECK(w.find_sha256(synthetic_source("y", "clip 39").sha256) == std::optional<std::string>(clip_name(39)));
        CHECK(w.add_clip(synthetic_clip(5, 2, 98), synthetic_source(clip_name(3) + ".bvh", "new")).id == clip_name(3) + "-2");
        w.commit();
    }
    const Database after(db_path);
    CHECK(after.clips().size() == 41);
    const ValidationReport report = validate_database(db_path);
    INFO(all_violations(report));
    CHECK(report.ok());
}

TEST_CASE("store: a clip attribute of the wrong type is named with its path", "[store][bad]") {
    TempDir dir("clip_attr_type");
    const auto db_path = dir / "db.h5";
    {
        DatabaseWriter w(db_path);
        for (int k = 0; k < 12; ++k)
            w.add_clip(synthetic_clip(10, 2, static_cast<unsigned>(k)), synthetic_source(clip_name(k) + ".bvh", std::to_string(k)));
        w.commit();
    }
    const std::string victim = clip_name(5);
    const auto script = dir / "damage.py";
    {
        std::ofstream out(script);
        out << "import h5py, sys\n"
               "with h5py.File(sys.argv[1], 'r+') as f:\n"
               "    g = f['/clips/" << victim << "']\n"
               "    del g.attrs['frame_rate']\n"
               "    g.attrs['frame_rate'] = 'sixty'\n"
               "    del g.attrs['source_format']\n";
    }
    const CommandResult py = run_command("/usr/bin/python3 " + quoted(script.string()) + " " + quoted(db_path.string()));
    if (py.exit_code != 0) {
        WARN("h5py is not available to /usr/bin/python3, the damage was not made: " + py.err);
        return;
    }
    const Database db(db_path);
    try {
        (void)db.clips();
        FAIL("expected a StoreError");
    } catch (const StoreError& e) {
        const std::string what = e.what();
        INFO(what);
        CHECK(what.find("/clips/" + victim) != std::string::npos);
        CHECK(what.find("attribute 'frame_rate': expected a scalar float64, found string scalar") != std::string::npos);
    }
    const auto other = db.find_clip(clip_name(4));
    REQUIRE(other);
    CHECK(other->frames == 10);
}
