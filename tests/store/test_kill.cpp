// Acceptance 5a: an import killed with SIGKILL at any moment leaves the previous database valid and
// byte-identical; the temporary files of killed processes are removed by the next import. The same
// for `mocapdb pack` (issue 14, acceptance 5), first pack and replacing pack.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <chrono>
#include <string>
#include <vector>
#include <thread>

#include "mocapdb/store/database.hpp"
#include "mocapdb/store/sha256.hpp"
#include "mocapdb/store/validate.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

std::size_t temp_files_of(const std::filesystem::path& target) {
    std::size_t n = 0;
    for (const auto& e : std::filesystem::directory_iterator(target.parent_path()))
        if (e.path().filename().string().rfind(target.filename().string() + ".tmp-mocapdb-", 0) == 0) ++n;
    return n;
}

/// Starts `mocapdb ARGS...` and kills it with SIGKILL after `delay`. Returns true when the kill hit
/// a running process (false: it had already finished by itself).
bool run_and_kill(const std::vector<std::string>& args, std::chrono::milliseconds delay) {
    const std::string cli = cli_path();
    std::vector<char*> argv;
    std::vector<std::string> storage = args;
    storage.insert(storage.begin(), "mocapdb");
    for (std::string& a : storage) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, STDOUT_FILENO);
        ::dup2(null, STDERR_FILENO);
        ::execv(cli.c_str(), argv.data());
        ::_exit(127);
    }
    std::this_thread::sleep_for(delay);
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

bool import_and_kill(const std::filesystem::path& input, const std::filesystem::path& db, std::chrono::milliseconds delay) {
    return run_and_kill({"import", input.string(), "-o", db.string()}, delay);
}

}  // namespace

TEST_CASE("kill -9 during an import leaves the previous file valid and complete", "[store][shared][acceptance]") {
    const auto amc_dir = datasets_dir() / "cmu-asfamc";
    const auto bvh_dir = datasets_dir() / "cmu-walkrun-pfnn";
    MOCAPDB_REQUIRE_SHARED(amc_dir);
    MOCAPDB_REQUIRE_SHARED(bvh_dir);
    TempDir dir("kill");
    const auto db = dir / "cmu.h5";
    const CommandResult base = run_cli("import " + quoted(bvh_dir.string()) + " --fps 60 -o " + quoted(db.string()));
    INFO(base.output);
    REQUIRE(base.exit_code == 0);
    const std::string previous = sha256_hex(file_bytes(db));

    std::size_t killed = 0;
    for (const int ms : {20, 150, 400, 900, 1600, 2500, 4000}) {
        const bool hit = import_and_kill(amc_dir, db, std::chrono::milliseconds(ms));
        INFO("killed after " << ms << " ms: " << (hit ? "mid-import" : "the import had finished"));
        if (!hit) {
            // It finished first: then the file is the complete new database.
            CHECK(Database(db).clips().size() == 215);
            break;
        }
        ++killed;
        CHECK(sha256_hex(file_bytes(db)) == previous);
        const Database reopened(db);
        CHECK(reopened.clips().size() == 33);
        CHECK(reopened.load_clip("16_15_60fps").frame_count() == 236);
    }
    CHECK(killed >= 3);
    WARN(killed << " imports killed mid-write; " << temp_files_of(db) << " temporary files left by them");
    CHECK(validate_database(db).ok());

    // The next import succeeds, and removes the temporaries of the killed (dead) processes.
    const CommandResult full = run_cli("import " + quoted(amc_dir.string()) + " -o " + quoted(db.string()));
    INFO(full.output);
    REQUIRE(full.exit_code == 0);
    CHECK(temp_files_of(db) == 0);
    // ... and the segments the killed sessions had begun (nothing links to them).
    CHECK(database_disk_bytes(db) == Database(db).file_size());
    CHECK(Database(db).clips().size() == 215);
    CHECK(validate_database(db).ok());
}

TEST_CASE("kill -9 during pack leaves the previous file valid and byte-identical", "[store][shared][packed][acceptance]") {
    const auto bvh_dir = datasets_dir() / "cmu-walkrun-pfnn";
    MOCAPDB_REQUIRE_SHARED(bvh_dir);
    TempDir dir("kill-pack");
    const auto db = dir / "walks.h5";
    const CommandResult base = run_cli("import " + quoted(bvh_dir.string()) + " --fps 60 -o " + quoted(db.string()));
    INFO(base.output);
    REQUIRE(base.exit_code == 0);

    // First pack (no tier yet), then a replacing pack over a tier at 1 cm.
    for (const bool replacing : {false, true}) {
        INFO((replacing ? "replacing pack" : "first pack"));
        if (replacing) REQUIRE(run_cli("pack " + quoted(db.string()) + " --max-error-cm 1").exit_code == 0);
        const std::string previous = sha256_hex(file_bytes(db));
        std::size_t killed = 0;
        for (const int ms : {30, 300, 700, 1200, 2000}) {
            std::vector<std::string> args = {"pack", db.string(), "--max-error-cm", "0.5"};
            if (replacing) args.push_back("--force");
            const bool hit = run_and_kill(args, std::chrono::milliseconds(ms));
            INFO("killed after " << ms << " ms: " << (hit ? "mid-pack" : "the pack had finished"));
            if (!hit) break;  // it finished first: the file is the new database (checked below)
            if (sha256_hex(file_bytes(db)) != previous) {
                // The kill came after the commit's atomic switch, while the process was still reporting
                // or exiting (seen once under a loaded -j2 run): then the file must be the complete new
                // database, never a mix. Later kills would compare against the wrong file: stop.
                const auto now = Database(db).packed();
                REQUIRE(now.has_value());
                CHECK(now->max_error_cm == 0.5);
                CHECK(validate_database(db).ok());
                break;
            }
            ++killed;
        }
        CHECK(killed >= 2);
        const Database view(db);
        CHECK(view.clips().size() == 33);
        const auto tier = view.packed();
        if (killed == 5) {
            CHECK(tier.has_value() == replacing);
            if (replacing) CHECK(tier->max_error_cm == 1.0);
        }
        CHECK(validate_database(db).ok());
        if (!replacing && tier) {
            // The last pack completed before its kill: start the replacing round from no tier.
            DatabaseWriter w(db);
            w.remove_packed();
            w.commit();
        }
    }
}
