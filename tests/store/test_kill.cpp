// Acceptance 5a: an import killed with SIGKILL at any moment leaves the previous database valid and
// byte-identical; the temporary files of killed processes are removed by the next import.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <chrono>
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

/// Starts `mocapdb import INPUT -o DB` and kills it with SIGKILL after `delay`. Returns true when
/// the kill hit a running import (false: it had already finished by itself).
bool import_and_kill(const std::filesystem::path& input, const std::filesystem::path& db, std::chrono::milliseconds delay) {
    const std::string cli = cli_path();
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, STDOUT_FILENO);
        ::dup2(null, STDERR_FILENO);
        ::execl(cli.c_str(), "mocapdb", "import", input.c_str(), "-o", db.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    std::this_thread::sleep_for(delay);
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
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
    CHECK(Database(db).clips().size() == 215);
    CHECK(validate_database(db).ok());
}
