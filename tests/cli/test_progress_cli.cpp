// Issue #16: progress on every command that can take over a second. The library reports through a
// ProgressCallback (done rising to total) and never prints; the CLI draws a bar on stderr only when
// stdout and stderr are terminals, so output in pipes, files and these tests is unchanged.
// Real data: walks of CMU subject 16.
#include <catch2/catch.hpp>

#include <algorithm>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/rank_search.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/validate.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

// Every report of one operation.
struct Recorder {
    std::vector<Progress> reports;
    std::vector<std::string> items;
    ProgressCallback callback() {
        return [this](const Progress& p) {
            reports.push_back({p.done, p.total, {}});
            items.emplace_back(p.item);
        };
    }
    // done never decreases, never exceeds total, total is fixed and the last report is done == total.
    void check_complete(std::uint64_t expected_total) const {
        REQUIRE(!reports.empty());
        for (std::size_t i = 0; i < reports.size(); ++i) {
            INFO("report " << i << ": " << reports[i].done << " / " << reports[i].total);
            CHECK(reports[i].total == expected_total);
            CHECK(reports[i].done <= reports[i].total);
            if (i > 0) CHECK(reports[i].done >= reports[i - 1].done);
        }
        CHECK(reports.back().done == expected_total);
    }
};

std::string walk_files(int first, int last) {
    std::string files;
    for (int t = first; t <= last; ++t)
        files += " " + quoted((datasets_dir() / "cmu-asfamc" / ("16_" + std::to_string(t) + ".amc")).string());
    return files;
}

}  // namespace

TEST_CASE("progress: set building, alignment, rank search and validation report done rising to total",
          "[cli][progress][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    TempDir dir("progress");
    const auto file = dir / "walks.h5";
    const CommandResult imported = run_cli("import" + walk_files(15, 20) + " -o " + quoted(file.string()));
    INFO(imported.output);
    REQUIRE(imported.exit_code == 0);
    const Database db(file);
    std::vector<std::string> ids;
    for (const ClipRecord& r : db.clips()) ids.push_back(r.id);
    REQUIRE(ids.size() == 6);

    Recorder built;
    SetBuildOptions options;
    options.name = "walks";
    options.extractors.push_back(ParameterExtractor::parse("speed"));
    options.progress = built.callback();
    const MotionSet set = build_motion_set(ids, [&](const std::string& id) { return db.load_clip(id); }, options);
    built.check_complete(ids.size());
    CHECK(built.items.front() == ids.front());  // the clip just done
    CHECK(built.items.back() == ids.back());

    std::vector<Clip> samples;
    for (const SampleRef& s : set.samples) samples.push_back(db.load_clip(s.clip));
    Recorder aligned;
    AlignOptions align;
    align.frames = 20;
    align.progress = aligned.callback();
    const AlignedSet a = align_samples(samples, align);
    aligned.check_complete(2 * samples.size());

    Recorder searched;
    const compression::PreparedSet prepared =
        compression::prepare_set(a.tensor, compression::position_error_weights(*samples.front().skeleton));
    const compression::JointErrorMeter meter(samples.front().skeleton, a.tensor);
    compression::search_ranks_for_max_error(prepared, meter, 1.0, searched.callback());
    REQUIRE(!searched.reports.empty());
    searched.check_complete(searched.reports.back().total);
    CHECK(searched.reports.back().total >= 2);

    Recorder validated;
    ValidateOptions vo;
    vo.progress = validated.callback();
    CHECK(validate_database(file, vo).ok());
    validated.check_complete(2 * ids.size());

    // Without a callback nothing changes.
    const MotionSet again = build_motion_set(ids, [&](const std::string& id) { return db.load_clip(id); },
                                             [&] { SetBuildOptions o = options; o.progress = {}; return o; }());
    CHECK(again.parameters == set.parameters);
}

TEST_CASE("progress: off a terminal the commands print exactly what they printed before", "[cli][progress][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    MOCAPDB_REQUIRE_CLI();
    TempDir dir("progress-cli");
    const std::string db = quoted((dir / "walks.h5").string());
    CommandResult r = run_cli("import" + walk_files(15, 20) + " -o " + db);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.empty());
    for (const std::string& args :
         {"set create " + db + " --name walks --clips '16_*' --extract speed turn", "align " + db + " --set walks --frames 20",
          "compress " + db + " --set walks --max-error-cm 1", "validate " + db,
          "report " + db + " --set walks --targets 1 --no-hooi"}) {
        r = run_cli(args);
        INFO(args << "\nstdout: " << r.out << "\nstderr: " << r.err);
        CHECK(r.exit_code == 0);
        CHECK(r.err.empty());                                 // no bar, no stray carriage returns
        CHECK(r.out.find('\r') == std::string::npos);
        CHECK(!r.out.empty());
    }
    r = run_cli("set create " + db + " --name walks2 --clips '16_*' --segment none --extract speed turn");
    CHECK(r.out == "set 'walks2': 6 samples (whole clips) from 6 clips, 2 parameters (extract:speed,turn)\n"
                   "repaired solver dropouts in 1 clip (6 joint runs of up to 7 frames): 16_15; 'mocapdb set show' lists "
                   "them\n");
}

TEST_CASE("progress: on a terminal a bar is drawn on stderr and the result line is the same", "[cli][progress][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    MOCAPDB_REQUIRE_CLI();
    if (run_command("script -qec true /dev/null").exit_code != 0) {
        WARN("SKIPPED: script(1) cannot give the command a terminal here");
        return;
    }
    TempDir dir("progress-tty");
    const std::string db = quoted((dir / "walks.h5").string());
    REQUIRE(run_cli("import" + walk_files(15, 20) + " -o " + db).exit_code == 0);
    // script(1) runs the command on a pseudo-terminal (stdout and stderr both) and copies it out.
    const std::string command = quoted(cli_path()) + " set create " + db + " --name walks --clips '16_*' --segment none --extract speed";
    const CommandResult r = run_command("script -qec " + quoted(command) + " /dev/null");
    INFO(r.output);
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("set create [") != std::string::npos);  // the bar (then erased with \r)
    CHECK(r.out.find("set 'walks': 6 samples (whole clips) from 6 clips, 1 parameters (extract:speed)") != std::string::npos);
}
