// Acceptance on the shared CMU clips (skipped when ../shared/datasets is absent):
//  1. importing both folders into one file succeeds, validate passes, info --json lists 215 clips
//     (182 AMC + 33 BVH) with the frame counts the parsers read from the sources;
//  2. exporting every clip reproduces the source channel values, in the source's units, to 1e-4
//     (all 215 clips: AMC clips written as AMC + ASF, BVH clips as BVH, re-read with the parsers).
// One test case, so the folders are imported once.
#include <catch2/catch.hpp>

#include <map>
#include <sstream>

#include "mocapdb/io/amc_writer.hpp"
#include "mocapdb/io/asf_amc.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/store/database.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

/// Channel values in the skeleton's source units (degrees or radians; source length unit).
FrameMatrix in_source_units(const Clip& clip) {
    const Skeleton& s = *clip.skeleton;
    FrameMatrix out = clip.channels;
    for (std::size_t j = 0; j < s.size(); ++j)
        for (std::size_t k = 0; k < s.joint(j).channels.size(); ++k) {
            const auto col = static_cast<Eigen::Index>(s.first_channel(j) + k);
            const double scale = is_rotation(s.joint(j).channels[k])
                                     ? (s.source_units().degrees ? 180.0 / kPi : 1.0)
                                     : 1.0 / s.source_units().cm_per_unit;
            out.col(col) *= scale;
        }
    return out;
}

struct Comparison {
    std::size_t clips = 0;
    double worst = 0.0;
    std::string worst_clip;
};

void compare(const std::string& id, const Clip& source, const Clip& exported, Comparison& c) {
    INFO("clip " << id);
    REQUIRE(exported.frame_count() == source.frame_count());
    REQUIRE(exported.channels.cols() == source.channels.cols());
    const double err = (in_source_units(exported) - in_source_units(source)).cwiseAbs().maxCoeff();
    if (err > c.worst) {
        c.worst = err;
        c.worst_clip = id;
    }
    ++c.clips;
    CHECK(err <= 1e-4);
}

std::string frames_key(const std::string& id, std::size_t frames) {
    return "{\"id\":\"" + id + "\",\"frames\":" + std::to_string(frames) + ",";
}

}  // namespace

TEST_CASE("shared CMU folders: import both, validate, info --json, export reproduces the sources",
          "[store][shared][acceptance]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    TempDir dir("shared");
    const auto amc_dir = folder_for_this_build(datasets_dir() / "cmu-asfamc", ".amc", dir.path());
    const auto bvh_dir = folder_for_this_build(datasets_dir() / "cmu-walkrun-pfnn", ".bvh", dir.path());
    const std::size_t n_amc = count_files(amc_dir, ".amc");  // 182 and 33 in a release build
    const std::size_t n_bvh = count_files(bvh_dir, ".bvh");
    const std::string n_all = std::to_string(n_amc + n_bvh);
    const auto db_path = dir / "cmu.h5";

    // 1. Import: AMC at 120 Hz, then the PFNN BVH files at their true 60 Hz, appending.
    const CommandResult amc = run_cli("import " + quoted(amc_dir.string()) + " -o " + quoted(db_path.string()));
    INFO(amc.output);
    REQUIRE(amc.exit_code == 0);
    CHECK(amc.output.find("imported " + std::to_string(n_amc) + " clips (0 skipped as duplicates)") != std::string::npos);
    const CommandResult bvh =
        run_cli("import " + quoted(bvh_dir.string()) + " --fps 60 -o " + quoted(db_path.string()));
    INFO(bvh.output);
    REQUIRE(bvh.exit_code == 0);
    CHECK(bvh.output.find("imported " + std::to_string(n_bvh) + " clips (0 skipped as duplicates)") != std::string::npos);
    CHECK(bvh.output.find("now holds " + n_all + " clips") != std::string::npos);
    if (std::filesystem::exists(bvh_dir / "08_04_60fps.bvh"))
        CHECK(bvh.output.find("08_04_60fps.bvh:") != std::string::npos);  // the reader's warning is shown

    // Re-importing identical files adds nothing and leaves the file as it was.
    const std::string before = file_bytes(db_path);
    const CommandResult again = run_cli("import " + quoted(bvh_dir.string()) + " -o " + quoted(db_path.string()));
    INFO(again.output);
    CHECK(again.exit_code == 0);
    CHECK(again.output.find("imported 0 clips (" + std::to_string(n_bvh) + " skipped as duplicates)") != std::string::npos);
    // Past a few (10), duplicates are counted in one line rather than listed one per file (#16).
    if (n_bvh > 10) {
        CHECK(again.output.find(std::to_string(n_bvh) + " files skipped: already stored (same sha256)") !=
              std::string::npos);
        CHECK(again.output.find("02_01_60fps.bvh: skipped") == std::string::npos);
    } else {
        CHECK(again.output.find("02_01_60fps.bvh: skipped") != std::string::npos);
    }
    CHECK(file_bytes(db_path) == before);

    const CommandResult valid = run_cli("validate " + quoted(db_path.string()));
    INFO(valid.output);
    CHECK(valid.exit_code == 0);
    CHECK(valid.output.find("valid mocapdb format " + std::to_string(kDatabaseFormatVersion) + " file") != std::string::npos);

    const CommandResult info = run_cli("info " + quoted(db_path.string()) + " --json");
    REQUIRE(info.exit_code == 0);
    CHECK(info.output.find("\"clip_count\":" + n_all + ",") != std::string::npos);

    // 2. Every clip against its source file, re-read with the parsers.
    const Database db(db_path);
    const auto records = db.clips();
    REQUIRE(records.size() == n_amc + n_bvh);
    std::map<std::string, std::shared_ptr<const Skeleton>> asf;
    Comparison amc_cmp, bvh_cmp;
    std::size_t amc_count = 0, bvh_count = 0;
    for (const ClipRecord& r : records) {
        const Clip stored = db.load_clip(r.id);
        Clip source;
        Clip exported;
        if (r.source.format == "amc") {
            ++amc_count;
            auto& skeleton = asf[r.source.skeleton_file];
            if (!skeleton) skeleton = read_asf(amc_dir / r.source.skeleton_file);
            source = read_amc(amc_dir / r.source.file_name, skeleton);
            // Export as the CLI does (ASF + AMC text), then parse both back.
            std::ostringstream asf_text, amc_text;
            write_asf(asf_text, *stored.skeleton);
            write_amc(amc_text, stored);
            auto reread_skeleton = std::make_shared<const Skeleton>(parse_asf(asf_text.str(), r.id + ".asf"));
            CHECK(reread_skeleton->same_structure(*skeleton, 1e-9));
            exported = parse_amc(amc_text.str(), r.id + ".amc", reread_skeleton);
            compare(r.id, source, exported, amc_cmp);
        } else {
            ++bvh_count;
            BvhReadOptions o;
            o.frame_rate = 60.0;
            source = read_bvh(bvh_dir / r.source.file_name, o);
            CHECK(is_bvh_compatible(*stored.skeleton));  // written as it is, channel for channel
            std::ostringstream text;
            BvhWriteOptions wo;
            wo.cm_per_unit = stored.skeleton->source_units().cm_per_unit;
            write_bvh(text, stored, wo);
            exported = parse_bvh(text.str(), r.id + ".bvh", o);
            compare(r.id, source, exported, bvh_cmp);
        }
        CHECK(stored.frame_rate == source.frame_rate);
        CHECK(stored.channels == source.channels);  // stored losslessly: bit-exact
        CHECK(info.output.find(frames_key(r.id, source.frame_count())) != std::string::npos);
    }
    CHECK(amc_count == n_amc);
    CHECK(bvh_count == n_bvh);
    WARN("export round trip: " << amc_cmp.clips << " AMC clips, worst " << amc_cmp.worst << " (" << amc_cmp.worst_clip
                               << "); " << bvh_cmp.clips << " BVH clips, worst " << bvh_cmp.worst << " ("
                               << bvh_cmp.worst_clip << "), in source units");

    // The CLI export, in both formats, to files; never overwriting without --force.
    const auto out_amc = dir / "02_01.amc";
    const CommandResult e1 = run_cli("export " + quoted(db_path.string()) + " --clip 02_01 -o " + quoted(out_amc.string()));
    INFO(e1.output);
    REQUIRE(e1.exit_code == 0);
    Comparison cli_cmp;
    compare("02_01 (cli)", read_amc(amc_dir / "02_01.amc", read_asf(amc_dir / "02.asf")),
            read_amc(out_amc, read_asf(dir / "02_01.asf")), cli_cmp);
    const auto out_bvh = dir / "02_01.bvh";
    const CommandResult e2 =
        run_cli("export " + quoted(db_path.string()) + " --clip 02_01_60fps -o " + quoted(out_bvh.string()));
    INFO(e2.output);
    REQUIRE(e2.exit_code == 0);
    BvhReadOptions o60;
    o60.frame_rate = 60.0;
    compare("02_01_60fps (cli)", read_bvh(bvh_dir / "02_01_60fps.bvh", o60), read_bvh(out_bvh, o60), cli_cmp);
    const CommandResult e3 = run_cli("export " + quoted(db_path.string()) + " --clip 02_01 -o " + quoted(out_amc.string()));
    CHECK(e3.exit_code == 1);
    CHECK(e3.output.find("exists (pass --force to overwrite it)") != std::string::npos);
    CHECK(run_cli("export " + quoted(db_path.string()) + " --clip 02_01 -o " + quoted(out_amc.string()) + " --force")
              .exit_code == 0);
}
