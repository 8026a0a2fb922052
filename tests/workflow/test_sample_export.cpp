// A set sample back at its own timing in-process (workflow/sample_export.hpp, issue #17; `mocapdb export
// --set S --sample I`): from the aligned tensor it has the sample's own frames and stays close to the
// captured clip; from the compressed model it stays close to the tensor's.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/sample_export.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

TEST_CASE("workflow: a set sample at its own timing from the tensor and from the model", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase w = make_walk_database("workflow_sample_export", WalkStage::Compressed);
    const Database db(w.path);
    const workflow::AlignedSetData data = workflow::load_aligned_set(db, "walks");
    const Eigen::Index n = 3;
    const Clip from_tensor = workflow::sample_at_own_timing(data, data.aligned.tensor, n, "walks_3");
    const SampleRef& ref = data.set.samples[static_cast<std::size_t>(n)];
    CHECK(from_tensor.name == "walks_3");
    CHECK(from_tensor.frame_count() == ref.frame_count());
    CHECK(from_tensor.frame_rate == data.frame_rate);
    // Close to the captured frames (resampled through the warp: not exact).
    const Clip captured = sample_frames(data.set, static_cast<std::size_t>(n), db.load_clip(ref.clip));
    REQUIRE(captured.frame_count() == from_tensor.frame_count());
    const Eigen::Index root_x = 0;
    CHECK((captured.channels.col(root_x) - from_tensor.channels.col(root_x)).cwiseAbs().maxCoeff() < 5.0);

    const auto stored = db.load_model("walks");
    REQUIRE(stored);
    const Clip from_model = workflow::sample_at_own_timing(data, stored->model.reconstruct(), n, "m");
    REQUIRE(from_model.frame_count() == from_tensor.frame_count());
    CHECK((from_model.channels - from_tensor.channels).cwiseAbs().maxCoeff() < 5.0);

    CHECK_THROWS_AS(workflow::sample_at_own_timing(data, data.aligned.tensor, 12, "x"), InvalidArgument);
    CHECK_THROWS_AS(workflow::sample_at_own_timing(data, data.aligned.tensor, -1, "x"), InvalidArgument);
}
