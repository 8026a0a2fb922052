// workflow::load_motion_model reads only the aligned set's timing and shape (issue #16, acceptance 4:
// the load proportional to the model, not to the aligned tensor). The compressed model it builds equals,
// bit for bit, the one built from the whole aligned set; the tensor's values are not read, so damage
// there does not stop it, while the naive model (which uses them) still reports the damage; damaged
// warps, which the compressed model uses, are refused.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "mocapdb/store/database.hpp"
#include "mocapdb/store/storage_extents.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

const WalkDatabase& load_model_walks() {
    static const WalkDatabase w = make_walk_database("workflow_load_model", WalkStage::Compressed);
    return w;
}

// A few parameters: two samples' own and two between and beyond them.
std::vector<VecX> queries(const MotionSet& set) {
    const VecX mean = set.parameters.colwise().mean().transpose();
    VecX beyond = mean;
    beyond(1) *= 1.3;
    return {set.parameters.row(0).transpose(), set.parameters.row(5).transpose(), mean, beyond};
}

// The same model: the same poses, coefficients, timing and reliability at every query, bit for bit.
void check_same_model(const synthesis::SynthesisModel& a, const synthesis::SynthesisModel& b, const MotionSet& set) {
    REQUIRE(a.dofs() == b.dofs());
    REQUIRE(a.frames() == b.frames());
    REQUIRE(a.samples() == b.samples());
    CHECK(a.report().kernel_precomputed == b.report().kernel_precomputed);
    CHECK(a.kernel_fit().status == b.kernel_fit().status);
    CHECK(a.kernel_fit().key == b.kernel_fit().key);
    synthesis::Workspace wa, wb;
    for (const VecX& c : queries(set)) {
        INFO("c = " << c.transpose());
        VecX ca(a.coefficient_size()), cb(b.coefficient_size());
        a.coefficients(c, ca, wa);
        b.coefficients(c, cb, wb);
        CHECK(ca == cb);
        CHECK(a.timing(c).warp == b.timing(c).warp);
        CHECK(a.reliability(c) == b.reliability(c));
        const MatX pa = a.motion_poses(c), pb = b.motion_poses(c);
        REQUIRE(pa.rows() == pb.rows());
        REQUIRE(pa.cols() == pb.cols());
        CHECK(pa == pb);
    }
}

// Inverts 4 bytes in the middle of the dataset's first stored chunk (a full chunk of deflated bytes).
void damage(const std::filesystem::path& file, const std::string& dataset) {
    const auto extents = dataset_extents(file, dataset);
    REQUIRE(!extents.empty());
    const ByteExtent chunk = extents.front();
    REQUIRE(chunk.size > 16);
    std::fstream f(chunk.file, std::ios::in | std::ios::out | std::ios::binary);  // the segment holding it
    REQUIRE(f);
    for (std::uint64_t k = 0; k < 4; ++k) {
        const auto at = static_cast<std::streamoff>(chunk.offset + chunk.size / 2 + k);
        char c = 0;
        f.seekg(at);
        f.read(&c, 1);
        c = static_cast<char>(~c);
        f.seekp(at);
        f.write(&c, 1);
    }
}

}  // namespace

TEST_CASE("workflow: load_aligned_timing gives the aligned set's warps and shape", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const Database db(load_model_walks().path);
    const workflow::AlignedSetData full = workflow::load_aligned_set(db, "walks");
    const workflow::AlignedTimingData timing = workflow::load_aligned_timing(db, "walks");
    CHECK(timing.timing.dofs() == full.aligned.dofs());
    CHECK(timing.timing.frames() == full.aligned.frames());
    CHECK(timing.timing.samples() == full.aligned.samples());
    CHECK(timing.timing.warps == full.aligned.warps);
    CHECK(timing.timing.inverse_warp_increments() == full.aligned.inverse_warp_increments());
    CHECK(timing.set.parameters == full.set.parameters);
    CHECK(timing.skeleton == full.skeleton);  // the database's cached skeleton
    CHECK(timing.frame_rate == full.frame_rate);
}

TEST_CASE("workflow: the compressed model loaded without the aligned tensor equals the one from the whole set",
          "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const Database db(load_model_walks().path);
    const workflow::AlignedSetData full = workflow::load_aligned_set(db, "walks");
    const auto stored = db.load_model("walks");
    REQUIRE(stored.has_value());
    synthesis::SynthesisOptions options;
    options.kernel_fit = db.load_kernel_fit("walks");
    REQUIRE(options.kernel_fit.has_value());  // `compress` stores it
    const synthesis::MotionModel from_full(stored->model, full.aligned, full.set, full.skeleton, full.frame_rate,
                                           options);
    const auto loaded = workflow::load_motion_model(db, "walks");
    CHECK(loaded->report().kernel_precomputed);
    CHECK(loaded->report().system_precomputed);  // the stored factorization was used
    check_same_model(*loaded, from_full, full.set);
    // The same model when the system is factorized again at load (the stored one dropped).
    options.kernel_fit->system.reset();
    const synthesis::MotionModel refactorized(stored->model, full.aligned, full.set, full.skeleton, full.frame_rate,
                                              options);
    CHECK(refactorized.report().kernel_precomputed);
    CHECK_FALSE(refactorized.report().system_precomputed);
    check_same_model(*loaded, refactorized, full.set);
}

TEST_CASE("workflow: load_motion_model does not read the aligned tensor (damage there stops only the naive model) "
          "but refuses damaged warps",
          "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    TempDir dir("workflow_load_model_damage");
    const std::filesystem::path path = dir / "walks.h5";
    const std::string tensor = "/sets/walks/aligned/tensor", warps = "/sets/walks/aligned/warps";

    copy_database(load_model_walks().path, path);
    damage(path, tensor);
    {
        const Database db(path);
        CHECK_THROWS_AS(workflow::load_naive_motion_model(db, "walks"), ChecksumError);
        CHECK_THROWS_WITH(workflow::load_naive_motion_model(db, "walks"), Contains("checksum mismatch in dataset " + tensor));
        CHECK_THROWS_AS(workflow::load_aligned_set(db, "walks"), ChecksumError);
        // The compressed model does not read the tensor's values: the same model as from the intact file.
        const auto loaded = workflow::load_motion_model(db, "walks");
        const auto intact = workflow::load_motion_model(Database(load_model_walks().path), "walks");
        check_same_model(*loaded, *intact, db.load_set("walks"));
    }

    std::filesystem::remove(path);
    std::filesystem::remove_all(path.string() + ".d");
    copy_database(load_model_walks().path, path);
    damage(path, warps);
    const Database db(path);
    CHECK_THROWS_AS(workflow::load_motion_model(db, "walks"), ChecksumError);
    CHECK_THROWS_WITH(workflow::load_motion_model(db, "walks"), Contains("checksum mismatch in dataset " + warps));
    CHECK_THROWS_WITH(workflow::load_naive_motion_model(db, "walks"), Contains("checksum mismatch in dataset " + warps));
}
