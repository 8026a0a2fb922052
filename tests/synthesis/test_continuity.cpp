// Issue #15, acceptance 3: synthesis is continuous in c. With the nugget filtered (measurement noise,
// not a jump at the samples), moving c by 1e-4 standard deviations from any sample moves no joint by
// more than 0.5 cm at any aligned frame. On subject 16's walks (CMU) and on the procedural reaches.
// Also: the leave-one-out z-scores of the coefficient kernel have mean z^2 near 1 (the prediction
// variance is calibrated), and rho <= 0.5 at 3 standard deviations outside the samples' box.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/procedural/humanoid.hpp"
#include "mocapdb/procedural/parametric_set.hpp"
#include "mocapdb/procedural/reach.hpp"
#include "mocapdb/synthesis/kernel_fit.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "shared_clips.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::synthesis;

namespace {

// Clips, their set and its aligned form (the skeleton: the first clip's).
using Samples = test::Subject16Set;

Samples cmu_walks() { return test::subject16_set({11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 47}, 20); }

Samples reaches() {
    procedural::ReachGrid grid;  // bearing -90..90 deg x height 60..160 cm, 5 x 3
    procedural::ParametricSet p = procedural::generate_reach_set(grid);
    Samples r;
    r.set.name = "reach";
    r.set.parameter_names = {"angle", "height"};
    r.set.parameter_units = {"deg", "cm"};
    r.set.parameters = p.parameters.leftCols(2);  // the distance axis is constant
    for (std::size_t i = 0; i < p.clips.size(); ++i) r.set.samples.push_back({p.clips[i].name, 0, p.clips[i].frame_count()});
    r.clips = std::move(p.clips);
    AlignOptions o;
    o.frames = 20;
    r.aligned = align_samples(r.clips, o);
    return r;
}

std::unique_ptr<MotionModel> model_of(const Samples& s) {
    const auto skeleton = s.clips.front().skeleton;
    const VecX weight = compression::position_error_weights(*skeleton);
    const compression::SetModel sm = compression::fit_set_model(
        s.aligned.tensor, weight, {s.aligned.dofs(), s.aligned.frames(), s.aligned.samples()}, tensor::TuckerMethod::Hosvd);
    return std::make_unique<MotionModel>(sm, s.aligned, s.set, skeleton, 120.0);
}

// Largest joint displacement (cm) over the aligned frames between the motions at c and c + dc.
double largest_jump(const MotionModel& m, const VecX& c, const VecX& dc) {
    Workspace ws;
    VecX a(m.dofs()), b(m.dofs());
    double worst = 0.0;
    for (Eigen::Index t = 0; t < m.frames(); ++t) {
        m.pose(c, static_cast<double>(t), a, ws);
        m.pose(c + dc, static_cast<double>(t), b, ws);
        const MatX pa = compression::pose_joint_positions(*m.skeleton(), a);
        const MatX pb = compression::pose_joint_positions(*m.skeleton(), b);
        for (Eigen::Index j = 0; j + 2 < pa.rows(); j += 3)
            worst = std::max(worst, (pa.middleRows(j, 3) - pb.middleRows(j, 3)).norm());
    }
    return worst;
}

void check_continuity(const Samples& s, const char* what) {
    const auto m = model_of(s);
    INFO(what << ": variogram " << m->report().model.to_string() << ", fit "
              << kriging::to_string(m->report().fit_status));
    REQUIRE(m->kernel().options().filter_nugget);
    double worst = 0.0;
    for (Eigen::Index i = 0; i < m->samples(); ++i)
        for (Eigen::Index k = 0; k < m->parameters(); ++k)
            for (const double side : {1.0, -1.0}) {
                VecX dc = VecX::Zero(m->parameters());
                dc(k) = side * 1e-4 * m->scaling().scale(k);
                worst = std::max(worst, largest_jump(*m, s.set.parameters.row(i).transpose(), dc));
            }
    INFO("largest joint jump for a 1e-4 sd step off a sample: " << worst << " cm");
    CHECK(worst <= 0.5);

    // rho <= 0.5 at 3 standard deviations outside the samples' box, along every axis.
    for (Eigen::Index k = 0; k < m->parameters(); ++k) {
        VecX c = s.set.parameters.colwise().mean().transpose();
        c(k) = s.set.parameters.col(k).maxCoeff() + 3.0 * m->scaling().scale(k);
        INFO("axis " << k << ": rho 3 sd outside " << m->reliability(c));
        CHECK(m->reliability(c) <= 0.5);
        c(k) = s.set.parameters.col(k).minCoeff() - 3.0 * m->scaling().scale(k);
        CHECK(m->reliability(c) <= 0.5);
    }

    // Leave-one-out z-scores of the coefficient kernel on the values its variogram describes (the
    // core slices; the variogram of their distances has the sum of the values' variances as its sill, so
    // z_i^2 sums over the values): mean z^2 = 1 for a calibrated variance; a factor 3 either way flags a
    // wrong sill.
    const kriging::LooResult loo = m->kernel().leave_one_out(core_slice_values(m->set_model()));
    const double mean_z2 = loo.zscore.squaredNorm() / static_cast<double>(loo.zscore.rows());
    INFO("LOO mean z^2 " << mean_z2);
    CHECK(mean_z2 > 1.0 / 3.0);
    CHECK(mean_z2 < 3.0);
}

// The reach target the synthesized motion reaches (as the demo measures it), as bearing (deg) and
// height (cm).
Eigen::Vector2d reached(const Clip& clip) {
    const std::optional<Vec3> hold = procedural::reach_hold_point(clip);
    REQUIRE(hold);
    const Vec3& h = *hold;
    return {std::atan2(h.x(), h.z()) * 180.0 / kPi, h.y()};
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
    const Eigen::Map<const VecX> x(a.data(), static_cast<Eigen::Index>(a.size()));
    const Eigen::Map<const VecX> y(b.data(), static_cast<Eigen::Index>(b.size()));
    const VecX dx = x.array() - x.mean(), dy = y.array() - y.mean();
    return dx.dot(dy) / std::sqrt(dx.squaredNorm() * dy.squaredNorm());
}

}  // namespace

TEST_CASE("on the reaches, low reliability means a missed target", "[synthesis][reliability]") {
    // Issue #15 acceptance 2: Pearson(rho, constraint error) <= -0.6 on the procedural reach set, over a
    // grid covering the samples' box and one standard deviation beyond it on each side.
    const Samples s = reaches();
    const auto m = model_of(s);
    const VecX lo = s.set.parameters.colwise().minCoeff().transpose() - m->scaling().scale;
    const VecX hi = s.set.parameters.colwise().maxCoeff().transpose() + m->scaling().scale;
    std::vector<double> rho, err;
    const int k = 9;
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
            VecX c(2);
            c << lo(0) + (hi(0) - lo(0)) * i / (k - 1), lo(1) + (hi(1) - lo(1)) * j / (k - 1);
            const Eigen::Vector2d got = reached(m->motion(c));
            rho.push_back(m->reliability(c));
            err.push_back(((got - c).array() / m->scaling().scale.array()).matrix().norm());
        }
    const double r = pearson(rho, err);
    INFO("variogram " << m->report().model.to_string() << "; Pearson(rho, error) over " << rho.size() << " points: " << r);
    CHECK(r <= -0.6);
}

TEST_CASE("synthesis is continuous in c on CMU walks", "[synthesis][shared][continuity]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    check_continuity(cmu_walks(), "CMU walks 16");
}

TEST_CASE("synthesis is continuous in c on procedural reaches", "[synthesis][continuity]") {
    check_continuity(reaches(), "procedural reaches");
}
