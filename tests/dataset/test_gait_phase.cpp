// Gait cycles cut at the same phase: the walks and runs of subject 16 (the phase-mixing
// finding) and the procedural walk.
#include <catch2/catch.hpp>

#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/dataset/gait_phase.hpp"
#include "mocapdb/dataset/phase_check.hpp"
#include "mocapdb/dataset/segmentation.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "shared_data.hpp"

using namespace mocapdb;

namespace {

std::vector<std::string> clips(int first, int last, int except = -1) {
    std::vector<std::string> out;
    for (int k = first; k <= last; ++k)
        if (k != except) out.push_back("16_" + std::to_string(k));
    return out;
}

// Share of samples whose left foot is ahead at each of `points` evenly spaced phases of the sample
// (0 = its first frame, 1 = its last), as the aligned frames of a DTW-aligned set would see them.
std::vector<double> left_ahead_share(const std::vector<std::pair<VecX, SampleRef>>& samples, int points) {
    std::vector<double> share(static_cast<std::size_t>(points), 0.0);
    for (const auto& [separation, s] : samples)
        for (int k = 0; k < points; ++k) {
            const double phase = static_cast<double>(k) / (points - 1);
            const auto f = static_cast<Eigen::Index>(s.begin + static_cast<std::size_t>(phase * static_cast<double>(s.end - 1 - s.begin) + 0.5));
            if (separation[f] > 0) share[static_cast<std::size_t>(k)] += 1.0 / static_cast<double>(samples.size());
        }
    return share;
}

// How many times the right foot takes the lead by more than 10 cm within a sample.
int right_foot_leads(const VecX& separation, const SampleRef& s) {
    int leads = 0, state = 0;
    for (auto f = static_cast<Eigen::Index>(s.begin); f < static_cast<Eigen::Index>(s.end); ++f) {
        if (separation[f] > 10.0) state = 1;
        if (separation[f] < -10.0 && state >= 0) {
            ++leads;
            state = -1;
        }
    }
    return leads;
}

}  // namespace

TEST_CASE("gait cycles of subject 16 start at one phase", "[segment][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    std::vector<std::string> ids = clips(11, 34);
    ids.push_back("16_47");
    for (const auto& r : clips(36, 56, 47)) ids.push_back(r);
    std::vector<std::pair<VecX, SampleRef>> whole, cycles;
    std::vector<Clip> walk_clips, walk_cycles;  // the walks (16_11..16_34, 16_47) for the phase check
    std::size_t without_cycle = 0;
    for (const std::string& id : ids) {
        const Clip clip = read_clip(test::datasets_dir() / "cmu-asfamc" / (id + ".amc"));
        const VecX separation = forward_foot_separation(clip);
        whole.push_back({separation, {id, 0, clip.frame_count()}});
        const bool walk = id <= "16_34" || id == "16_47";
        GaitCycleOptions middle;
        middle.max_per_clip = 1;
        const auto found = gait_cycles(clip, id, middle);
        if (found.empty()) {
            ++without_cycle;
            continue;
        }
        REQUIRE(found.size() == 1);
        const SampleRef& c = found.front();
        INFO(id << " cycle " << c.begin << "-" << c.end);
        CHECK(separation[static_cast<Eigen::Index>(c.begin)] >= 0.0);  // starts as the left foot passes
        if (c.begin > 0) CHECK(separation[static_cast<Eigen::Index>(c.begin) - 1] < 0.0);
        const double seconds = static_cast<double>(c.frame_count() - 1) / clip.frame_rate;
        CHECK((seconds > 0.3 && seconds < 1.6));
        CHECK(right_foot_leads(separation, c) == 1);
        if (walk) {
            walk_clips.push_back(clip);
            walk_cycles.push_back(slice(clip, c.begin, c.end));
        }
        // The middle one of all the clip's cycles.
        const auto all = gait_cycles(clip, id);
        CHECK(c.begin == all[(all.size() - 1) / 2].begin);
        cycles.push_back({separation, c});
    }
    INFO(without_cycle << " of " << ids.size() << " clips have no whole gait cycle");
    CHECK(without_cycle <= 3);  // walks that stop after a step, runs of about one second
    // Same forward foot at every phase for (nearly) all cycles; whole clips mix them at the ends.
    const auto cycle_share = left_ahead_share(cycles, 21);
    const auto whole_share = left_ahead_share(whole, 21);
    // Agreement away from the phases where the feet pass each other (0, 1/2, 1: level feet).
    double worst_cycle = 1.0, worst_whole = 1.0;
    for (std::size_t k = 0; k < cycle_share.size(); ++k) {
        const double phase = static_cast<double>(k) / 20.0;
        if (std::abs(phase - 0.5) < 0.12 || phase < 0.07 || phase > 0.93) continue;
        worst_cycle = std::min(worst_cycle, std::max(cycle_share[k], 1.0 - cycle_share[k]));
        worst_whole = std::min(worst_whole, std::max(whole_share[k], 1.0 - whole_share[k]));
    }
    INFO("least agreement on the forward foot: cycles " << worst_cycle << ", whole clips " << worst_whole);
    CHECK(worst_cycle >= 0.9);
    CHECK(worst_whole < 0.75);

    // The phase check `align` prints, on DTW-aligned walks: whole clips blend the feet at the ends.
    AlignOptions align;
    align.frames = 40;
    const VecX whole_agreement = check_phase(walk_clips, align_samples(walk_clips, align)).share;
    const VecX cycle_agreement = check_phase(walk_cycles, align_samples(walk_cycles, align)).share;
    REQUIRE(whole_agreement.size() == 40);
    REQUIRE(cycle_agreement.size() == 40);
    INFO("phase check, lowest share: whole walks " << whole_agreement.minCoeff() << ", cycles " << cycle_agreement.minCoeff());
    CHECK(whole_agreement.minCoeff() < 0.7);
    CHECK(cycle_agreement.minCoeff() >= 0.85);
    CHECK(cycle_agreement.mean() >= 0.97);
}

TEST_CASE("gait cycles of subject 105's long walk are single strides", "[segment][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Clip clip = read_clip(test::datasets_dir() / "cmu-asfamc" / "105_01.amc");
    const VecX separation = forward_foot_separation(clip);
    const auto cycles = gait_cycles(clip, "105_01");
    REQUIRE(cycles.size() >= 10);
    for (const SampleRef& c : cycles) {
        INFO("cycle " << c.begin << "-" << c.end);
        CHECK(right_foot_leads(separation, c) == 1);  // the right foot leads once: one stride, not two
    }
}

TEST_CASE("no gait cycles when the feet do not alternate", "[segment]") {
    VecX still = VecX::Constant(240, 2.0);  // feet side by side, jitter below the swing threshold
    for (Eigen::Index f = 0; f < still.size(); ++f) still[f] += (f % 2 ? 1.5 : -1.5);
    CHECK(left_foot_passes(still).empty());
    VecX swing(240);
    for (Eigen::Index f = 0; f < swing.size(); ++f) swing[f] = 30.0 * std::sin(2.0 * kPi * static_cast<double>(f) / 100.0 + 0.3);
    const auto passes = left_foot_passes(swing);
    REQUIRE(passes.size() == 2);
    CHECK(passes[1] - passes[0] == 100);
}
