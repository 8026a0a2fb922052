// Synthesis with a periodic control parameter (issue #15): subject 16's walks by bearing (direction of
// travel, period 2 pi) and speed. A request and the same request a turn later are one motion, in single
// and batched queries; the set's reliability uses the circle too.
#include <catch2/catch.hpp>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/synthesis/naive_motion_model.hpp"
#include "shared_clips.hpp"
#include "shared_data.hpp"

using namespace mocapdb;

TEST_CASE("a periodic bearing: c and c + 2 pi synthesize the same motion", "[synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    test::Subject16Set s = test::subject16_set({11, 13, 15, 17, 19, 21, 23, 25, 27, 29}, 16);
    const std::vector<ParameterExtractor> bearing{ParameterExtractor::parse("bearing")};
    s.set.parameter_names[0] = "bearing";
    for (std::size_t i = 0; i < s.clips.size(); ++i)
        s.set.parameters(static_cast<Eigen::Index>(i), 0) = extract_parameters(s.clips[i], 0, s.clips[i].frame_count(), bearing)(0);
    set_parameter_period(s.set, "bearing", 2.0 * kPi);
    const auto skeleton = s.clips.front().skeleton;
    const synthesis::NaiveMotionModel model(s.aligned, s.set, skeleton, 120.0, compression::position_error_weights(*skeleton));
    REQUIRE(model.scaling().has_periodic_axis());

    MatX c(3, 2);
    c << 0.3, 120.0, -2.9, 140.0, 3.1, 100.0;
    MatX shifted = c;
    shifted.col(0).array() += 2.0 * kPi;
    shifted(2, 0) -= 4.0 * kPi;  // and a turn back
    for (const double t : {0.0, 7.5, 15.0}) {
        for (Eigen::Index q = 0; q < c.rows(); ++q) {
            const VecX a = model.pose(c.row(q).transpose(), t);
            const VecX b = model.pose(shifted.row(q).transpose(), t);
            CHECK((a - b).cwiseAbs().maxCoeff() < 1e-7);
        }
        MatX batch(s.aligned.dofs(), c.rows());
        synthesis::BatchWorkspace ws;
        model.poses(shifted, t, batch, ws);
        for (Eigen::Index q = 0; q < c.rows(); ++q)
            CHECK((batch.col(q) - model.pose(shifted.row(q).transpose(), t)).cwiseAbs().maxCoeff() < 1e-9);
    }
    // Reliability: the same at c and a turn later.
    const VecX rho = model.reliability_batch(c);
    const VecX rho_shifted = model.reliability_batch(shifted);
    CHECK(model.reliability(c.row(0).transpose()) == Approx(rho(0)).margin(1e-12));
    CHECK((rho - rho_shifted).cwiseAbs().maxCoeff() < 1e-9);
}
