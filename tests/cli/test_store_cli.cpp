// The database subcommands through the real executable: exit codes and messages.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <vector>

#include "mocapdb/io/bvh.hpp"
#include "mocapdb/store/database.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

std::filesystem::path write_small_bvh(const TempDir& dir, const std::string& name, unsigned seed) {
    std::filesystem::create_directories(dir / "clips");
    const auto path = dir / ("clips/" + name);
    write_bvh(path, synthetic_clip(25, 2, seed));
    return path;
}

}  // namespace

TEST_CASE("cli: import, info and validate on small files", "[store][cli]") {
    TempDir dir("cli");
    write_small_bvh(dir, "a.bvh", 1);
    write_small_bvh(dir, "b.bvh", 2);
    { std::ofstream(dir / "clips/notes.txt") << "not a clip\n"; }  // ignored in folders
    {
        std::ofstream m(dir / "manifest.csv");
        m << "file,subject,description,labels\na,7,\"first, short\",walk;test\n";
    }
    const auto db = dir / "db.h5";
    const CommandResult r = run_cli("import " + quoted((dir / "clips").string()) + " --fps 50 --manifest " +
                                    quoted((dir / "manifest.csv").string()) + " -o " + quoted(db.string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(r.output.find("imported 2 clips (0 skipped as duplicates): 50 frames") != std::string::npos);
    const Database d(db);
    const auto a = d.find_clip("a");
    REQUIRE(a.has_value());
    CHECK(a->frame_rate == 50.0);
    CHECK(a->source.subject == "7");
    CHECK(a->source.description == "first, short");
    CHECK(a->source.labels == std::vector<std::string>{"walk", "test"});

    const CommandResult info = run_cli("info " + quoted(db.string()));
    INFO(info.output);
    CHECK(info.exit_code == 0);
    CHECK(info.output.find("clips       2: 50 frames") != std::string::npos);
    const CommandResult json = run_cli("info " + quoted(db.string()) + " --json");
    CHECK(json.output.find("\"subject\":\"7\",\"description\":\"first, short\",\"labels\":[\"walk\",\"test\"]") !=
          std::string::npos);
    CHECK(run_cli("validate " + quoted(db.string())).exit_code == 0);

    // --force starts over; without it an import appends.
    const CommandResult f = run_cli("import " + quoted((dir / "clips/a.bvh").string()) + " --force -o " + quoted(db.string()));
    INFO(f.output);
    CHECK(f.exit_code == 0);
    CHECK(Database(db).clips().size() == 1);
}

TEST_CASE("cli: refusals", "[store][cli]") {
    TempDir dir("cli-refuse");
    const auto clip = write_small_bvh(dir, "a.bvh", 1);
    const auto text = dir / "precious.h5";
    { std::ofstream(text) << "my data\n"; }

    const CommandResult foreign = run_cli("import " + quoted(clip.string()) + " -o " + quoted(text.string()));
    INFO(foreign.output);
    CHECK(foreign.exit_code == 1);
    CHECK(foreign.output.find("precious.h5: cannot open as an HDF5 file") != std::string::npos);
    CHECK(foreign.output.find("--force replaces the file") != std::string::npos);
    CHECK(file_bytes(text) == "my data\n");

    const CommandResult invalid = run_cli("validate " + quoted(text.string()));
    CHECK(invalid.exit_code == 1);
    CHECK(invalid.output.find("not a valid mocapdb file: 1 violation") != std::string::npos);

    const CommandResult empty = run_cli("import " + quoted(dir.path().string() + "/") + " -o " + quoted((dir / "x.h5").string()));
    // the folder holds a.bvh: fine; an empty folder is refused
    CHECK(empty.exit_code == 0);
    std::filesystem::create_directories(dir / "empty");
    const CommandResult none = run_cli("import " + quoted((dir / "empty").string()) + " -o " + quoted((dir / "y.h5").string()));
    CHECK(none.exit_code == 1);
    CHECK(none.output.find("no .bvh or .amc files found") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir / "y.h5"));

    const auto db = dir / "x.h5";
    const CommandResult missing = run_cli("export " + quoted(db.string()) + " --clip nope -o " + quoted((dir / "o.bvh").string()));
    CHECK(missing.exit_code == 1);
    CHECK(missing.output.find("no clip 'nope'") != std::string::npos);
    const CommandResult amc = run_cli("export " + quoted(db.string()) + " --clip a -o " + quoted((dir / "o.amc").string()));
    CHECK(amc.exit_code == 1);
    CHECK(amc.output.find("cannot be written as AMC") != std::string::npos);
    const CommandResult type = run_cli("export " + quoted(db.string()) + " --clip a -o " + quoted((dir / "o.txt").string()));
    CHECK(type.exit_code == 1);
    CHECK(type.output.find("unsupported output type") != std::string::npos);

    for (const char* cmd : {"import", "validate", "export"}) {
        const CommandResult help = run_cli(std::string(cmd) + " --help");
        CHECK(help.exit_code == 0);
        CHECK(help.output.find("Example") != std::string::npos);
    }
}

TEST_CASE("cli: import --keep-going stores the good files and lists the bad ones", "[store][cli]") {
    TempDir dir("keepgoing");
    for (unsigned k = 1; k <= 3; ++k) write_small_bvh(dir, "good" + std::to_string(k) + ".bvh", k);
    { std::ofstream(dir / "clips/broken.bvh") << "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n"; }
    const auto db = dir / "db.h5";
    // Without the flag the first bad file stops the import and nothing is stored.
    CommandResult r = run_cli("import " + quoted((dir / "clips").string()) + " -o " + quoted(db.string()));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("broken.bvh:"));
    CHECK(!std::filesystem::exists(db));
    // With it the good files are stored, the bad one is named with its line, and the exit code says so.
    r = run_cli("import " + quoted((dir / "clips").string()) + " --keep-going -o " + quoted(db.string()));
    INFO(r.output);
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("mocapdb: error: ") && Contains("broken.bvh:5") &&
                          Contains("1 file could not be imported") && Contains("the other clips were stored"));
    CHECK_THAT(r.out, Contains("imported 3 clips"));
    CHECK(Database(db).clips().size() == 3);
    // Re-importing a folder of stored files: one line for the duplicates, not one per file, past a few.
    for (unsigned k = 4; k <= 15; ++k) write_small_bvh(dir, "more" + std::to_string(k) + ".bvh", k);
    std::filesystem::remove(dir / "clips/broken.bvh");
    REQUIRE(run_cli("import " + quoted((dir / "clips").string()) + " -o " + quoted(db.string())).exit_code == 0);
    r = run_cli("import " + quoted((dir / "clips").string()) + " -o " + quoted(db.string()));
    INFO(r.output);
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.output, Contains("15 files skipped: already stored"));
}

TEST_CASE("cli: empty files in a folder import are reported per file, the others stored, nothing half-made",
          "[store][cli]") {
    TempDir dir("import-empty");
    write_small_bvh(dir, "good1.bvh", 1);
    write_small_bvh(dir, "good2.bvh", 2);
    { std::ofstream(dir / "clips/empty.bvh"); }
    { std::ofstream(dir / "clips/blank.bvh") << "\n  \n"; }
    const auto db = dir / "db.h5";
    CommandResult r = run_cli("import " + quoted((dir / "clips").string()) + " -o " + quoted(db.string()));
    INFO(r.output);
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("empty.bvh: the file is empty (0 bytes)") && Contains("blank.bvh: the file is empty") &&
                          Contains("2 files could not be imported") && Contains("the other clips were stored"));
    CHECK_THAT(r.out, Contains("imported 2 clips"));
    CHECK(Database(db).clips().size() == 2);

    // A folder of nothing but empty files: no database, no segment folder, no lock file left behind.
    std::filesystem::create_directories(dir / "hollow");
    { std::ofstream(dir / "hollow/a.bvh"); }
    { std::ofstream(dir / "hollow/b.amc"); }
    auto listing = [&] {
        std::vector<std::string> names;
        for (const auto& e : std::filesystem::directory_iterator(dir.path())) names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    };
    const std::vector<std::string> before = listing();
    const auto hollow = dir / "hollow.h5";
    r = run_cli("import " + quoted((dir / "hollow").string()) + " -o " + quoted(hollow.string()));
    INFO(r.output);
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("a.bvh: the file is empty") && Contains("b.amc: the file is empty") &&
                          Contains("no clip was stored"));
    CHECK_THAT(r.out, Contains("was not created"));
    CHECK(listing() == before);

    // The same through a failed parse (no --keep-going): the import stops and leaves nothing either.
    { std::ofstream(dir / "hollow/c.bvh") << "HIERARCHY\nROOT Hips\n{\n"; }
    r = run_cli("import " + quoted((dir / "hollow").string()) + " -o " + quoted(hollow.string()));
    CHECK(r.exit_code == 1);
    CHECK(listing() == before);
}
