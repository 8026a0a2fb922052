// The tiny reference file of format version 1 (tests/data/reference-v1.h5), kept forever:
// - rebuilding it today gives the same structure (`h5dump -H` equals the committed dump);
// - the committed file still opens, loads the same values and validates.
// To regenerate after an intended format change (with a new format version and a CHANGELOG entry):
//   MOCAPDB_UPDATE_REFERENCE=1 build/tests/test_store "[reference]"
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <regex>

#include "mocapdb/store/database.hpp"
#include "mocapdb/store/validate.hpp"
#include "reference_database.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

const std::filesystem::path kReference = test_data_dir() / "reference-v1.h5";
const std::filesystem::path kReferenceDump = test_data_dir() / "reference-v1.h5dump.txt";

// h5dump -H without its first line (which names the file).
std::string header_dump(const std::filesystem::path& file) {
    const CommandResult r = run_command("h5dump -H " + quoted(file.string()));
    REQUIRE(r.exit_code == 0);
    const auto newline = r.output.find('\n');
    return r.output.substr(newline == std::string::npos ? 0 : newline + 1);
}

}  // namespace

TEST_CASE("reference file: rebuilding it gives the committed h5dump -H", "[store][reference]") {
    TempDir dir("reference");
    const auto rebuilt = dir / "reference-v1.h5";
    write_reference_database(rebuilt);
    const std::string dump = header_dump(rebuilt);
    if (std::getenv("MOCAPDB_UPDATE_REFERENCE") != nullptr) {
        std::filesystem::copy_file(rebuilt, kReference, std::filesystem::copy_options::overwrite_existing);
        std::ofstream(kReferenceDump, std::ios::binary) << "HDF5 \"reference-v1.h5\" {\n" << dump;
        WARN("reference file regenerated in " << test_data_dir().string());
    }
    REQUIRE(std::filesystem::exists(kReferenceDump));
    std::string committed = file_bytes(kReferenceDump);
    committed = committed.substr(committed.find('\n') + 1);
    CHECK(dump == committed);
}

TEST_CASE("reference file: the committed file opens, loads and validates", "[store][reference]") {
    REQUIRE(std::filesystem::exists(kReference));
    const ReferenceContent expected = reference_content();
    const Database db(kReference);
    const auto clips = db.clips();
    REQUIRE(clips.size() == 1);
    CHECK(clips[0].id == "tiny_walk");
    CHECK(clips[0].source.sha256 == expected.source.sha256);
    CHECK(clips[0].source.labels == expected.source.labels);
    const Clip clip = db.load_clip("tiny_walk");
    CHECK(clip.skeleton->same_structure(*expected.clip.skeleton, 0.0));
    CHECK(clip.channels == expected.clip.channels);
    CHECK(clip.frame_rate == expected.clip.frame_rate);
    const MotionSet set = db.load_set("tiny_set");
    CHECK(set.parameters == expected.set.parameters);
    CHECK(set.samples.size() == 2);
    const auto aligned = db.load_aligned("tiny_set");
    REQUIRE(aligned.has_value());
    const Eigen::Tensor<double, 0> diff = (aligned->tensor - expected.aligned.tensor).abs().maximum();
    CHECK(diff() == 0.0);
    CHECK(aligned->warps == expected.aligned.warps);
    CHECK(validate_database(kReference).ok());

    // h5dump reads element [s][t][d] = tensor(d, t, s) = d + 10 t + 100 s: (1, 2, 5) holds 125.
    const CommandResult r =
        run_command("h5dump -d /sets/tiny_set/aligned/tensor -s 1,2,5 -c 1,1,1 " + quoted(kReference.string()));
    INFO(r.output);
    CHECK(r.output.find("(1,2,5): 125") != std::string::npos);
}
