#include <catch2/catch.hpp>
#include <random>

#include "mocapdb/dataset/dtw.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/dataset/segmentation.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "shared_data.hpp"

using namespace mocapdb;

namespace {
std::vector<Clip> subject16_walks() {
    std::vector<Clip> clips;
    std::vector<std::string> trials;
    for (int t = 11; t <= 34; ++t) trials.push_back("16_" + std::to_string(t));
    trials.push_back("16_47");
    for (const auto& t : trials) clips.push_back(read_clip(test::datasets_dir() / "cmu-asfamc" / (t + ".amc")));
    return clips;
}
}  // namespace

TEST_CASE("DTW recovers a known time warp", "[dtw]") {
    // A 1-D signal and the same signal played with a non-linear clock.
    const int m = 120, n = 150;
    auto signal = [](double x) { return std::sin(x * 0.11) + 0.5 * std::sin(x * 0.037 + 1.0); };
    auto clock = [&](double j) { return (n - 1) * std::pow(j / (m - 1), 1.3); };  // sample frame shown at ref frame j
    MatX ref(1, m), sample(1, n);
    for (int j = 0; j < m; ++j) ref(0, j) = signal(j);
    // sample(i) = ref at the reference frame j whose clock is i (inverse of clock)
    for (int i = 0; i < n; ++i) sample(0, i) = signal((m - 1) * std::pow(static_cast<double>(i) / (n - 1), 1 / 1.3));
    MatX cost(n, m);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) cost(i, j) = std::abs(sample(0, i) - ref(0, j));
    const align::DtwPath path = align::dtw(cost);
    const VecX w = align::warp_from_path(path, n, m);
    double worst = 0;
    for (int j = 0; j < m; ++j) worst = std::max(worst, std::abs(w[j] - clock(j)));
    INFO("worst warp error " << worst << " frames");
    CHECK(worst < 3.0);
    CHECK(w[0] == 0.0);
    CHECK(w[m - 1] == n - 1);
    for (int j = 1; j < m; ++j) REQUIRE(w[j] > w[j - 1]);
}

TEST_CASE("DTW alignment of subject 16's walks beats linear resampling", "[align][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const std::vector<Clip> clips = subject16_walks();
    AlignOptions linear;
    linear.method = "linear";
    AlignOptions dtw_options;
    const AlignedSet a_linear = align_samples(clips, linear);
    const AlignedSet a_dtw = align_samples(clips, dtw_options);
    REQUIRE(a_dtw.reference == a_linear.reference);
    const double d_linear = mean_alignment_distance(clips, a_linear);
    const double d_dtw = mean_alignment_distance(clips, a_dtw);
    WARN("mean pose distance to the reference: linear " << d_linear << " cm, DTW " << d_dtw << " cm");
    CHECK(d_dtw < 0.8 * d_linear);  // at least 20% closer

    // The tensor: D × T × N, pose vectors of 31 rotating joints, warps strictly increasing.
    CHECK(a_dtw.dofs() == static_cast<Eigen::Index>(PoseLayout(*clips[0].skeleton).dof_count()));
    CHECK(a_dtw.dofs() == 90);  // root 6 + 28 CMU bones with rotation dofs
    CHECK(a_dtw.frames() == 100);
    CHECK(a_dtw.samples() == 25);
    CHECK_NOTHROW(validate(a_dtw));
    CHECK((a_dtw.inverse_warp_increments().array() > 0).all());
    // Exp-map branches agree across samples: at the first frame no sample's joint rotation vector is
    // farther than π from the reference's.
    for (Eigen::Index n = 0; n < a_dtw.samples(); ++n)
        for (Eigen::Index d = 6; d < a_dtw.dofs(); d += 3) {
            Vec3 a, b;
            for (int k = 0; k < 3; ++k) {
                a[k] = a_dtw.tensor(d + k, 0, n);
                b[k] = a_dtw.tensor(d + k, 0, static_cast<Eigen::Index>(a_dtw.reference));
            }
            REQUIRE((a - b).norm() < kPi);
        }
}

TEST_CASE("gait cycles of subject 105's long walk", "[segment][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Clip clip = read_clip(test::datasets_dir() / "cmu-asfamc" / "105_01.amc");
    const auto cycles = gait_cycles(clip, "105_01");
    INFO(cycles.size() << " cycles in " << clip.frame_count() << " frames");
    CHECK(cycles.size() >= 4);
    for (const SampleRef& c : cycles) {
        const double seconds = static_cast<double>(c.frame_count() - 1) / clip.frame_rate;
        CHECK((seconds >= 0.6 && seconds <= 2.0));
        CHECK(c.end <= clip.frame_count());
    }
    const auto windows = fixed_windows(clip, "105_01", 120, 60);
    CHECK(windows.size() == (clip.frame_count() - 120) / 60 + 1);
}

TEST_CASE("alignment refuses bad input", "[align]") {
    CHECK_THROWS_AS(align_samples({}), InvalidArgument);
    CHECK_THROWS_AS(align::dtw(MatX(0, 3)), InvalidArgument);
    MatX c = MatX::Ones(3, 3);
    c(1, 1) = std::nan("");
    CHECK_THROWS_AS(align::dtw(c), InvalidArgument);
}
