// The compression step in-process (workflow/set_compression.hpp, issue #17): a set of subject 16's
// walks compressed to a max joint error of 1 cm, measured and stored with its synthesis kernel;
// explicit ranks, HOOI, and the errors.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

const WalkDatabase& set_compression_walks() {
    static const WalkDatabase w = make_walk_database("workflow_compress", WalkStage::Aligned);
    return w;
}

}  // namespace

TEST_CASE("workflow: compress_set meets a max joint error and stores the model with its kernel", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& w = set_compression_walks();
    workflow::CompressRequest r;
    r.set = "walks";
    r.max_error_cm = 1.0;
    int calls = 0;
    r.progress = [&](const Progress&) { ++calls; };
    const workflow::CompressOutcome o = workflow::compress_set(w.path, r);
    CHECK(calls > 0);
    CHECK(o.criterion == "max joint error <= 1 cm");
    CHECK(o.target_met);
    CHECK(o.stats.max_cm <= 1.0);  // measured after forward kinematics on every joint, frame and sample
    CHECK(o.stats.rmse_cm <= o.stats.max_cm);
    CHECK(o.stats.p99_cm <= o.stats.max_cm);
    const tensor::Dims3 dims{w.aligned.aligned.dofs(), 40, 12};
    CHECK(o.dims == dims);
    const tensor::Ranks& ranks = o.model.tucker.ranks;
    for (std::size_t n = 0; n < 3; ++n) {
        CHECK(ranks[n] >= 1);
        CHECK(ranks[n] <= dims[n]);
    }
    CHECK(o.raw_bytes == static_cast<std::uint64_t>(4 * dims[0] * dims[1] * dims[2]));
    CHECK(o.bytes > 0);
    CHECK(o.ratio() > 1.0);
    CHECK(o.us_per_pose > 0.0);
    CHECK(o.kernel_stored);
    CHECK(o.kernel_fit_samples == 12);  // under SynthesisOptions::max_fit_samples: all of them
    CHECK_FALSE(o.kernel_variogram.empty());

    const Database db(w.path);
    const auto stored = db.load_model("walks");
    REQUIRE(stored.has_value());
    CHECK(stored->model.tucker.ranks == ranks);
    CHECK(stored->figures.max_cm == o.stats.max_cm);
    const auto kernel = db.load_kernel_fit("walks");
    REQUIRE(kernel.has_value());
    // The factorized system is stored with it (12 unique points).
    REQUIRE(kernel->system);
    CHECK(kernel->system->inverse.rows() == 12);
    CHECK(kernel->system->inverse.cols() == 12);
    CHECK(o.stored_bytes > 0);
    for (const SetRecord& s : db.sets())
        if (s.name == "walks") CHECK(s.model_stored_bytes == o.stored_bytes);

    // A looser target needs fewer parameters.
    r.max_error_cm = 5.0;
    const workflow::CompressOutcome loose = workflow::compress_set(w.path, r);
    CHECK(loose.target_met);
    CHECK(loose.stats.max_cm <= 5.0);
    CHECK(loose.bytes <= o.bytes);
}

TEST_CASE("workflow: compress_set with explicit ranks and HOOI, and its errors", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& w = set_compression_walks();
    workflow::CompressRequest r;
    r.set = "walks";
    r.ranks = tensor::Ranks{10, 6, 4};
    r.method = tensor::TuckerMethod::Hooi;
    const workflow::CompressOutcome o = workflow::compress_set(w.path, r);
    CHECK(o.criterion == "ranks 10x6x4");
    CHECK(o.target_met);
    CHECK(o.model.tucker.ranks == tensor::Ranks{10, 6, 4});
    CHECK(o.model.tucker.method == tensor::TuckerMethod::Hooi);
    CHECK(o.stats.max_cm > 0.0);  // measured on the HOOI model, not taken from the search
    CHECK(Database(w.path).load_model("walks")->model.tucker.method == tensor::TuckerMethod::Hooi);

    // Errors store nothing.
    r.ranks = tensor::Ranks{10, 41, 4};
    CHECK_THROWS_AS(workflow::compress_set(w.path, r), InvalidArgument);
    CHECK_THROWS_WITH(workflow::compress_set(w.path, r), Contains("rank 2 must be in [1, 40]"));
    workflow::SetRequest unaligned;
    unaligned.name = "few";
    unaligned.clips = {"16_11", "16_12", "16_13"};
    unaligned.segment = "none";
    unaligned.extract = {"speed"};
    workflow::create_set(w.path, unaligned);
    r.set = "few";
    r.ranks.reset();
    CHECK_THROWS_WITH(workflow::compress_set(w.path, r), Contains("set 'few'") && Contains("is not aligned"));
    CHECK_THROWS_AS(workflow::compress_set(w.path, r), Remediable);
    CHECK(Database(w.path).load_model("walks")->model.tucker.method == tensor::TuckerMethod::Hooi);
    CHECK_FALSE(Database(w.path).load_model("few").has_value());
}

TEST_CASE("workflow: a set without control parameters compresses, synthesis says why it cannot", "[workflow][shared]") {
    // Found while measuring #16: compress stopped after its rank search with an internal class's
    // message, because the synthesis kernel needs parameters. Real clips: subject 16's walks.
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    WalkDatabase w = make_walk_database("workflow_compress_noparams", WalkStage::Imported);
    workflow::SetRequest set;
    set.name = "plain";
    set.clips = {"16_*"};
    set.segment = "none";
    workflow::create_set(w.path, set);
    workflow::AlignRequest align;
    align.set = "plain";
    align.frames = 40;
    workflow::align_set(w.path, align);
    workflow::CompressRequest r;
    r.set = "plain";
    r.max_error_cm = 1.0;
    const workflow::CompressOutcome o = workflow::compress_set(w.path, r);
    CHECK(o.target_met);
    CHECK(o.stats.max_cm <= 1.0);
    CHECK_FALSE(o.kernel_stored);
    CHECK_THAT(o.kernel_not_stored_reason, Contains("no control parameters"));
    const Database db(w.path);
    CHECK(db.load_model("plain").has_value());
    CHECK_FALSE(db.load_kernel_fit("plain").has_value());
    CHECK_THROWS_WITH(workflow::load_motion_model(db, "plain", synthesis::SynthesisOptions{}),
                      Contains("set 'plain'") && Contains("has no control parameters"));
    CHECK_THROWS_AS(workflow::load_naive_motion_model(db, "plain", synthesis::SynthesisOptions{}), InvalidArgument);
}
