#pragma once
// Locating ../shared (datasets and peer reference results) from tests. Tests that need it SKIP with a
// clear message when the folder is absent; CI has it, so there they run.
#include <filesystem>
#include <string>

namespace mocapdb::test {

inline std::filesystem::path shared_dir() { return std::filesystem::path(MOCAPDB_SHARED_DIR); }
inline std::filesystem::path datasets_dir() { return shared_dir() / "datasets"; }
inline std::filesystem::path reference_dir() { return shared_dir() / "reference"; }
inline std::filesystem::path test_data_dir() { return std::filesystem::path(MOCAPDB_TEST_DATA_DIR); }
inline std::string cli_path() { return MOCAPDB_CLI_PATH; }

}  // namespace mocapdb::test

/// Skips the current test case (Catch2 v2 has no SKIP) when a shared folder is missing.
#define MOCAPDB_REQUIRE_SHARED(path)                                                              \
    do {                                                                                          \
        if (!std::filesystem::exists(path)) {                                                     \
            WARN("SKIPPED: shared data not found at " << (path).string()                          \
                                                      << " (tests read ../shared beside the repo)"); \
            return;                                                                               \
        }                                                                                         \
    } while (0)

/// Skips the current test case when the mocapdb CLI is not built in this tree.
#define MOCAPDB_REQUIRE_CLI()                                                  \
    do {                                                                       \
        if (mocapdb::test::cli_path().empty()) {                               \
            WARN("SKIPPED: the mocapdb CLI is not built in this tree");        \
            return;                                                            \
        }                                                                      \
    } while (0)
