// The training-window sampler (workflow/window_sampler.hpp, issue #17) in-process: reproducible by
// seed, windows equal to the clips' frames in their canonical frame from either tier, one rig only.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/not_found_error.hpp"
#include "mocapdb/workflow/import_files.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "mocapdb/workflow/window_sampler.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

/// Pose vectors (L x D, C order) of frames [begin, begin + L) of a clip, in their canonical frame.
std::vector<double> window_of(const Clip& clip, std::size_t begin, std::size_t length) {
    const Clip part = slice(clip, begin, begin + length);
    const MatX poses = to_pose_vectors(part, canonicalization_of(part));
    return std::vector<double>(poses.data(), poses.data() + poses.size());
}

}  // namespace

TEST_CASE("workflow: windows from subject 16's walks, lossless and packed", "[workflow][shared]") {
    const auto amc = datasets_dir() / "cmu-asfamc";
    MOCAPDB_REQUIRE_SHARED(amc);
    TempDir dir("workflow_windows");
    const auto db_path = dir / "walks.h5";
    {
        DatabaseWriter w(db_path, DatabaseWriter::Mode::OpenOrCreate);
        workflow::import_files(w, {amc / "16_11.amc", amc / "16_12.amc", amc / "16_13.amc"}, workflow::ImportOptions{});
        w.commit();
    }
    const std::size_t L = 40, B = 6;
    workflow::WindowSamplerOptions o;
    o.length = L;
    o.batch = B;
    o.seed = 9;

    SECTION("lossless: the same seed gives the same windows, equal to the clips' frames") {
        const Database db(db_path);
        workflow::WindowSampler a(db, o), b(db, o);
        CHECK_FALSE(a.from_packed());  // no packed tier yet
        const std::size_t V = a.values_per_frame();
        CHECK(V == PoseLayout(*db.load_skeleton(db.clips()[0].skeleton)).dof_count());
        std::vector<double> x(B * L * V), y(B * L * V);
        std::vector<workflow::WindowRef> refs(B);
        a.next(x.data(), refs.data());
        b.next(y.data());
        CHECK(x == y);
        std::uint64_t windows = 0;
        for (const auto& r : db.clips()) windows += r.frames - L + 1;
        CHECK(a.window_count() == windows);
        for (std::size_t k = 0; k < B; ++k) {
            const Clip clip = db.load_clip(a.clip_ids()[refs[k].clip]);
            const std::vector<double> expected = window_of(clip, refs[k].begin, L);
            // The decoded clip's world values with the window's rigid motion removed: equal but for rounding.
            double worst = 0.0;
            for (std::size_t i = 0; i < L * V; ++i) worst = std::max(worst, std::abs(x[k * L * V + i] - expected[i]));
            CHECK(worst < 1e-9);
        }
        a.next(x.data());
        CHECK(x != y);  // the stream moves on

        // float32 output: the same windows within float32 rounding, from a float32 cache.
        workflow::WindowSamplerOptions single = o;
        single.dtype = workflow::WindowDType::Float32;
        workflow::WindowSampler c(db, single);
        std::vector<float> z(B * L * V);
        c.next(z.data());
        double worst = 0.0;
        for (std::size_t i = 0; i < z.size(); ++i) worst = std::max(worst, std::abs(static_cast<double>(z[i]) - y[i]));
        CHECK(worst > 0.0);
        CHECK(worst < 1e-3);
        CHECK(c.cache_bytes() < b.cache_bytes());

        workflow::WindowSamplerOptions joints = o;
        joints.values = workflow::WindowValues::JointPositions;
        workflow::WindowSampler p(db, joints);
        CHECK(p.values_per_frame() == 3 * p.joint_names().size());
        std::vector<double> xyz(B * L * p.values_per_frame());
        p.next(xyz.data());
        // Canonical: the motion root starts above the origin, and nothing is far from it.
        for (std::size_t k = 0; k < B; ++k) CHECK(xyz[k * L * p.values_per_frame() + 1] > 50.0);
    }

    SECTION("packed: every joint within the tier's bound of the lossless window") {
        workflow::PackDatabaseOptions pack;
        pack.max_error_cm = 0.5;
        workflow::pack_database(db_path, pack);
        const Database db(db_path);
        workflow::WindowSamplerOptions lossless = o, packed = o;
        lossless.values = packed.values = workflow::WindowValues::JointPositions;
        lossless.source = workflow::WindowSource::Lossless;
        workflow::WindowSampler a(db, packed), b(db, lossless);
        CHECK(a.from_packed());
        std::vector<double> x(B * L * a.values_per_frame()), y(x.size());
        std::vector<workflow::WindowRef> ra(B), rb(B);
        a.next(x.data(), ra.data());
        b.next(y.data(), rb.data());
        for (std::size_t k = 0; k < B; ++k) CHECK((ra[k].clip == rb[k].clip && ra[k].begin == rb[k].begin));
        // Each window is in its own canonical frame, which the packed root defines within the bound
        // too: allow its heading's effect over a window's reach (a few cm), far below a real mismatch.
        double worst = 0.0;
        for (std::size_t i = 0; i < x.size(); i += 3) {
            const double dx = x[i] - y[i], dy = x[i + 1] - y[i + 1], dz = x[i + 2] - y[i + 2];
            worst = std::max(worst, std::sqrt(dx * dx + dy * dy + dz * dz));
        }
        CHECK(worst > 0.0);
        CHECK(worst < 3.0);
    }

    SECTION("errors name what is wrong") {
        const Database db(db_path);
        workflow::WindowSamplerOptions bad = o;
        bad.length = 100000;
        CHECK_THROWS_WITH(workflow::WindowSampler(db, bad), Contains("none of the 3 selected clips has 100000 frames"));
        bad = o;
        bad.clips = {"17_*"};
        CHECK_THROWS_WITH(workflow::WindowSampler(db, bad), Contains("no clip matches '17_*'"));
        bad.clips = {"17_01"};  // a plain name: a missing clip, not an empty match
        CHECK_THROWS_AS(workflow::WindowSampler(db, bad), NotFoundError);
        bad = o;
        bad.source = workflow::WindowSource::Packed;
        CHECK_THROWS_WITH(workflow::WindowSampler(db, bad), Contains("is not in the packed tier"));
        bad = o;
        bad.batch = 0;
        CHECK_THROWS_AS(workflow::WindowSampler(db, bad), InvalidArgument);
        workflow::WindowSampler s(db, o);
        std::vector<double> out(L * s.values_per_frame());
        CHECK_THROWS_WITH(s.window({0, 10000}, out.data()), Contains("beyond clip"));
    }
}

TEST_CASE("workflow: windows of a joint that turns past half a turn start on the principal branch",
          "[workflow]") {
    // A two-joint BVH rig whose child turns 2 full turns about Y: its exp map, continuous along the clip,
    // passes |v| = pi; a window starting beyond that starts on the principal branch, as the window's own
    // pose vectors do (the sampler re-tracks it from the decoded clip).
    TempDir dir("workflow_windows_turn");
    const auto bvh = dir / "turn.bvh";
    {
        std::ofstream out(bvh);
        out << "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation "
               "Yrotation\n JOINT Arm\n {\n  OFFSET 0 10 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n  End Site\n  {\n"
               "   OFFSET 10 0 0\n  }\n }\n}\nMOTION\nFrames: 200\nFrame Time: 0.0333333\n";
        for (int f = 0; f < 200; ++f)
            out << 0.5 * f << " 90 " << 0.25 * f << " 0 0 " << 0.1 * f << " 5 10 " << 3.6 * f << "\n";
    }
    const auto db_path = dir / "turn.h5";
    {
        DatabaseWriter w(db_path, DatabaseWriter::Mode::OpenOrCreate);
        workflow::import_files(w, {bvh}, workflow::ImportOptions{});
        w.commit();
    }
    const Database db(db_path);
    workflow::WindowSamplerOptions o;
    o.length = 30;
    o.source = workflow::WindowSource::Lossless;
    workflow::WindowSampler s(db, o);
    const Clip clip = db.load_clip(s.clip_ids()[0]);
    const std::size_t V = s.values_per_frame();
    std::vector<double> window(o.length * V);
    double worst = 0.0, largest = 0.0;
    for (std::size_t begin = 0; begin + o.length <= clip.frame_count(); begin += 7) {
        s.window({0, begin}, window.data());
        const std::vector<double> expected = window_of(clip, begin, o.length);
        for (std::size_t i = 0; i < window.size(); ++i) worst = std::max(worst, std::abs(window[i] - expected[i]));
        for (std::size_t f = 0; f < o.length; ++f)
            largest = std::max(largest, Vec3(window[f * V + 6], window[f * V + 7], window[f * V + 8]).norm());
    }
    CHECK(worst < 1e-9);
    CHECK(largest > kPi);  // windows do follow the joint past the principal branch's end
}
