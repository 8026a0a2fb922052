#include "mocapdb/eval/evaluation_plan.hpp"

#include <algorithm>
#include <sstream>

namespace mocapdb::eval {
namespace {

std::vector<std::string> clip_range(const std::string& subject, int first, int last,
                                    const std::vector<int>& skip = {}) {
    std::vector<std::string> out;
    for (int t = first; t <= last; ++t) {
        if (std::find(skip.begin(), skip.end(), t) != skip.end()) continue;
        out.push_back(subject + "_" + (t < 10 ? "0" : "") + std::to_string(t));
    }
    return out;
}

// Eight kernels: enough to exercise the kernel headroom in smoke runs.
KernelHeadroomOptions small_headroom_grid() {
    KernelHeadroomOptions o;
    o.exponents = {0.0, 1.5};
    o.ranges = {0.5, 2.0};
    o.nugget_shares = {0.0, 0.3};
    o.anisotropy = {1.0};
    return o;
}

EvalSetSpec walks_spec(Eigen::Index frames) {
    EvalSetSpec s;
    s.name = "walks16";
    s.description =
        "subject 16 walks: straight, veering and 90-degree turns at two speeds, plus slow walks (speed x turn grid)";
    s.clips = clip_range("16", 11, 34);
    s.clips.push_back("16_47");
    s.gait_cycles = true;  // phase-consistent samples: one gait cycle per clip
    s.max_cycles_per_clip = 1;
    s.extractors = {"turn", "speed"};
    s.frames = frames;
    return s;
}

}  // namespace

const char* to_string(EvalMode mode) {
    switch (mode) {
        case EvalMode::Full: return "full";
        case EvalMode::Quick: return "quick";
        case EvalMode::Tiny: return "tiny";
    }
    return "full";
}

EvalPlan make_eval_plan(EvalMode mode) {
    EvalPlan p;
    if (mode == EvalMode::Tiny) {
        EvalSetSpec s = walks_spec(12);
        s.clips = {"16_11", "16_13", "16_15", "16_17", "16_19", "16_21", "16_23", "16_25", "16_31"};
        p.sets.push_back({s, true, 3, true, true, true});
        p.constraint.points_per_axis_2d = 3;
        p.reduction.checkpoints = 2;
        p.reduction.random_orders = 1;
        p.compression_targets = {5.0};
        p.hooi = false;
        p.runtime_set = s.name;
        p.runtime.sizes = {5, 9};
        p.runtime.repeats = 1;
        p.headroom = small_headroom_grid();
        return p;
    }
    if (mode == EvalMode::Quick) {
        p.sets.push_back({walks_spec(30), true, 3, true, true, true});
        p.constraint.points_per_axis_2d = 6;
        p.reduction.checkpoints = 4;
        p.reduction.random_orders = 2;
        p.compression_targets = {2.0, 1.0};
        p.hooi = false;
        p.runtime_set = "walks16";
        p.runtime.sizes = {8, 16, 25};
        p.runtime.repeats = 1;
        p.headroom = small_headroom_grid();
        return p;
    }
    p.sets.push_back({walks_spec(40), true, 1, true, false, true});
    {
        EvalSetSpec s;
        s.name = "runs16";
        s.description = "subject 16 runs/jogs: straight, veering and 90-degree turns (speed x turn grid)";
        s.clips = clip_range("16", 36, 56, {47});
        s.gait_cycles = true;
        s.max_cycles_per_clip = 1;
        s.extractors = {"turn", "speed"};
        s.frames = 40;
        p.sets.push_back({s, true, 1, true, false, true});
    }
    {
        EvalSetSpec s;
        s.name = "jumps";
        s.description = "forward jumps of subjects 13, 16 and 105, parameterized by jump length";
        s.clips = {"13_11", "13_13", "13_19", "13_32"};
        for (const auto& c : clip_range("16", 5, 10, {8})) s.clips.push_back(c);
        for (const auto& c : clip_range("105", 39, 45)) s.clips.push_back(c);
        s.extractors = {"jump"};
        s.flight_windows = true;  // phase-consistent samples: the jump, not the standing around it
        s.frames = 40;
        p.sets.push_back({s, true, 1, true, false, true});
    }
    {
        EvalSetSpec s;
        s.name = "jumpturns105";
        s.description = "subject 105 jump turns (90 to 360 degrees, both directions), parameterized by turn angle";
        s.clips = clip_range("105", 46, 61, {57});
        s.extractors = {"turn"};
        s.flight_windows = true;  // as the forward jumps
        s.frames = 40;
        p.sets.push_back({s, true, 1, true, false, true});
    }
    {
        EvalSetSpec s;
        s.name = "gait105";
        s.description = "gait cycles segmented from subject 105's long styled walks (many samples from few clips)";
        s.clips = {"105_11", "105_13", "105_17", "105_19", "105_22", "105_29", "105_33"};
        s.gait_cycles = true;
        s.max_cycles_per_clip = 10;
        s.extractors = {"speed", "turn"};
        s.frames = 40;
        p.sets.push_back({s, true, 2, true, true, true});
    }
    p.constraint.points_per_axis_2d = 12;
    p.constraint.points_1d = 40;
    p.runtime_set = "gait105";
    p.runtime.sizes = {8, 16, 32, 60};
    p.runtime.repeats = 2;
    p.compression_targets = {2.0, 1.0, 0.5};
    p.hooi_sets = {"walks16"};
    return p;
}

SetMethods methods_for_set(const EvalSet& set, const std::vector<double>& tucker_targets) {
    SetMethods out;
    auto& m = out.methods;
    m.push_back({MethodKind::PerPoseKriging, "per-pose kriging", {0, 0, 0}, {}, {}});
    m.push_back({MethodKind::PerElementKriging, "per-element kriging", {0, 0, 0}, {}, {}});
    for (double t : tucker_targets) {
        std::ostringstream name;
        name << "tucker-" << t << "cm";
        m.push_back({MethodKind::TuckerKriging, name.str(), ranks_for_max_error(set, t), {}, {}});
        out.tucker_targets_cm.push_back(t);
    }
    // The error targets above keep every sample direction on these sets; a truncated sample mode
    // (a third of the samples, the loosest target's dof and time ranks) shows what compressing it costs.
    if (!tucker_targets.empty() && set.size() >= 6) {
        const double loosest = *std::max_element(tucker_targets.begin(), tucker_targets.end());
        tensor::Ranks ranks = ranks_for_max_error(set, loosest);
        ranks[2] = std::min<Eigen::Index>(ranks[2], (set.size() + 2) / 3);
        m.push_back({MethodKind::TuckerKriging, "tucker-R3=N/3", ranks, {}, {}});
        out.tucker_targets_cm.push_back(loosest);
    }
    m.push_back({MethodKind::NaiveKriging, "naive kriging", {0, 0, 0}, {}, {}});
    m.push_back({MethodKind::Rbf, "rbf", {0, 0, 0}, {}, {}});
    m.push_back({MethodKind::NearestNeighbour, "nn-blend k=3", {0, 0, 0}, {}, {}});
    m.push_back({MethodKind::TrendOnly, "trend only", {0, 0, 0}, {}, {}});
    return out;
}

}  // namespace mocapdb::eval
