#include "mocapdb/dataset/dropout_repair.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/rotation.hpp"

namespace mocapdb {
namespace {

// Rotation channel columns of joint j in its Euler order (outermost first), -1 for a missing axis.
std::array<int, 3> rotation_columns(const Skeleton& s, std::size_t j) {
    const auto ax = axes_of(s.joint(j).rotation_order);
    std::array<int, 3> cols{};
    for (int k = 0; k < 3; ++k) cols[k] = s.channel_column(j, static_cast<ChannelType>(3 + static_cast<int>(ax[k])));
    return cols;
}

Vec3 angles_at(const Clip& clip, const std::array<int, 3>& cols, std::size_t f) {
    Vec3 a = Vec3::Zero();
    for (int k = 0; k < 3; ++k)
        if (cols[k] >= 0) a[k] = clip.frame(f)[cols[k]];
    return a;
}

bool all_zero(const Clip& clip, const std::array<int, 3>& cols, std::size_t f) {
    for (int c : cols)
        if (c >= 0 && clip.frame(f)[c] != 0.0) return false;
    return true;
}

// Joints with rotation channels and, for each, its neighbours with rotation channels: the nearest
// such ancestor and the nearest such descendants (joints without rotation channels are passed
// through).
std::vector<std::vector<std::size_t>> rotation_neighbours(const Skeleton& s) {
    std::vector<std::vector<std::size_t>> out(s.size());
    for (std::size_t j = 0; j < s.size(); ++j) {
        if (!s.has_rotation(j)) continue;
        int a = s.joint(j).parent;
        while (a >= 0 && !s.has_rotation(static_cast<std::size_t>(a))) a = s.joint(static_cast<std::size_t>(a)).parent;
        if (a < 0) continue;
        out[j].push_back(static_cast<std::size_t>(a));
        out[static_cast<std::size_t>(a)].push_back(j);
    }
    return out;
}

struct Candidate {
    DropoutRun run;
    bool borders_moving = false;  // (2)
    bool accepted = false;
};

// (2): the connected group of exactly-zero joints around j at frame f borders a joint that is not zero.
bool group_borders_moving(const std::vector<std::vector<std::size_t>>& nb, const std::vector<std::vector<char>>& zero,
                          std::size_t j, std::size_t f) {
    std::vector<std::size_t> stack{j};
    std::vector<char> seen(nb.size(), 0);
    seen[j] = 1;
    while (!stack.empty()) {
        const std::size_t k = stack.back();
        stack.pop_back();
        for (std::size_t m : nb[k]) {
            if (seen[m]) continue;
            seen[m] = 1;
            if (!zero[m][f]) return true;
            stack.push_back(m);
        }
    }
    return false;
}

double channel_rotation_angle(const Skeleton& s, std::size_t j, const double* row) {
    return angle_between(Quat::Identity(), s.local_rotation(j, row));
}

// (3a), second half: every rotation channel's clean values lie on one side of 0 and reach within tol of it.
bool zero_is_limit(const Clip& clip, const std::array<int, 3>& cols, const std::vector<char>& zero, double tol) {
    for (int c : cols) {
        if (c < 0) continue;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (std::size_t f = 0; f < clip.frame_count(); ++f) {
            if (zero[f]) continue;
            lo = std::min(lo, clip.frame(f)[c]);
            hi = std::max(hi, clip.frame(f)[c]);
        }
        const bool at_low_edge = lo >= -tol && lo <= tol;
        const bool at_high_edge = hi <= tol && hi >= -tol;
        if (!at_low_edge && !at_high_edge) return false;
    }
    return true;
}

std::string frames_text(std::size_t begin, std::size_t end) {
    return end == begin + 1 ? std::to_string(begin) : std::to_string(begin) + "-" + std::to_string(end - 1);
}

}  // namespace

std::vector<DropoutRun> detect_dropouts(const Clip& clip, const DropoutOptions& options) {
    validate(clip);
    const Skeleton& s = *clip.skeleton;
    const std::size_t frames = clip.frame_count();
    const auto nb = rotation_neighbours(s);
    // zero[j][f]: joint j (with rotation channels) has every rotation channel exactly 0 at frame f.
    std::vector<std::vector<char>> zero(s.size(), std::vector<char>(frames, 0));
    std::vector<char> moves(s.size(), 0);
    for (std::size_t j = 0; j < s.size(); ++j) {
        if (!s.has_rotation(j)) continue;
        const auto cols = rotation_columns(s, j);
        for (std::size_t f = 0; f < frames; ++f) {
            zero[j][f] = all_zero(clip, cols, f) ? 1 : 0;
            if (!zero[j][f]) moves[j] = 1;
        }
    }
    std::vector<Candidate> cands;
    for (std::size_t j = 0; j < s.size(); ++j) {
        if (!s.has_rotation(j) || !moves[j]) continue;  // (1)
        const auto cols = rotation_columns(s, j);
        bool limit_known = false, limit = false;
        for (std::size_t b = 0; b < frames;) {
            if (!zero[j][b]) {
                ++b;
                continue;
            }
            std::size_t e = b;
            while (e < frames && zero[j][e]) ++e;
            Candidate c;
            c.run.joint = j;
            c.run.joint_name = s.joint(j).name;
            c.run.begin = b;
            c.run.end = e;
            if (b > 0) c.run.jump = channel_rotation_angle(s, j, clip.frame(b - 1));
            if (e < frames) c.run.jump = std::max(c.run.jump, channel_rotation_angle(s, j, clip.frame(e)));
            c.borders_moving = true;
            for (std::size_t f = b; f < e && c.borders_moving; ++f)
                c.borders_moving = group_borders_moving(nb, zero, j, f);
            if (c.borders_moving && c.run.jump >= options.min_jump) {
                if (!limit_known) {
                    limit = zero_is_limit(clip, cols, zero[j], options.limit_tolerance);
                    limit_known = true;
                }
                c.accepted = !limit;
            }
            cands.push_back(std::move(c));
            b = e;
        }
    }
    // (3b): runs overlapping an accepted run of an adjacent joint, until nothing changes.
    for (bool changed = true; changed;) {
        changed = false;
        for (Candidate& c : cands) {
            if (c.accepted || !c.borders_moving) continue;
            for (const Candidate& d : cands) {
                if (!d.accepted) continue;
                const auto& adj = nb[c.run.joint];
                if (std::find(adj.begin(), adj.end(), d.run.joint) == adj.end()) continue;
                if (d.run.begin < c.run.end && c.run.begin < d.run.end) {
                    c.accepted = true;
                    changed = true;
                    break;
                }
            }
        }
    }
    std::vector<DropoutRun> out;
    for (const Candidate& c : cands)
        if (c.accepted) out.push_back(c.run);
    return out;
}

void repair_dropouts(Clip& clip, const std::vector<DropoutRun>& runs) {
    validate(clip);
    const Skeleton& s = *clip.skeleton;
    const std::size_t frames = clip.frame_count();
    for (const DropoutRun& r : runs) {
        const std::string who = "repair_dropouts: run of joint " + std::to_string(r.joint) + " ('" + r.joint_name +
                                "') at frames [" + std::to_string(r.begin) + ", " + std::to_string(r.end) + ")";
        if (r.joint >= s.size() || !s.has_rotation(r.joint))
            throw InvalidArgument(who + ": the joint does not exist or has no rotation channels");
        if (r.begin >= r.end || r.end > frames)
            throw InvalidArgument(who + ": frames outside the clip's " + std::to_string(frames));
        if (r.begin == 0 && r.end == frames) throw InvalidArgument(who + ": no frame outside the run to repair from");
        const auto cols = rotation_columns(s, r.joint);
        const int channels = static_cast<int>(std::count_if(cols.begin(), cols.end(), [](int c) { return c >= 0; }));
        const Vec3 weights(cols[0] >= 0 ? 1.0 : 1e6, cols[1] >= 0 ? 1.0 : 1e6, cols[2] >= 0 ? 1.0 : 1e6);
        const bool has_before = r.begin > 0, has_after = r.end < frames;
        const Vec3 before = has_before ? angles_at(clip, cols, r.begin - 1) : Vec3::Zero();
        Vec3 after = has_after ? angles_at(clip, cols, r.end) : Vec3::Zero();
        if (has_before && has_after) after = unwrap_angles(after, before);
        const EulerOrder order = s.joint(r.joint).rotation_order;
        const Quat q0 = euler_to_quat(before, order), q1 = euler_to_quat(after, order);
        for (std::size_t f = r.begin; f < r.end; ++f) {
            Vec3 a;
            if (!has_before) {
                a = after;  // hold the nearest clean frame
            } else if (!has_after) {
                a = before;
            } else {
                const double t = static_cast<double>(f - (r.begin - 1)) / static_cast<double>(r.end - (r.begin - 1));
                const Vec3 linear = (1.0 - t) * before + t * after;
                a = channels == 3 ? matrix_to_euler_near(q0.slerp(t, q1).toRotationMatrix(), order, linear, weights)
                                  : linear;
            }
            for (int k = 0; k < 3; ++k)
                if (cols[k] >= 0) clip.channels(static_cast<Eigen::Index>(f), cols[k]) = a[k];
        }
    }
}

std::vector<RepairedFrames> repair_records(const std::string& clip_id, const std::vector<DropoutRun>& runs) {
    std::vector<RepairedFrames> out;
    for (const DropoutRun& r : runs) out.push_back({clip_id, r.joint_name, r.begin, r.end});
    return out;
}

Clip with_repairs(const Clip& clip, const std::string& clip_id, const std::vector<RepairedFrames>& repairs) {
    std::vector<DropoutRun> runs;
    for (const RepairedFrames& r : repairs) {
        if (r.clip != clip_id) continue;
        const auto j = clip.skeleton->find(r.joint);
        if (!j)
            throw InvalidArgument("clip '" + clip_id + "': a repair record names joint '" + r.joint +
                                  "', which its skeleton lacks");
        if (r.begin >= r.end || r.end > clip.frame_count())
            throw InvalidArgument("clip '" + clip_id + "': a repair record of joint '" + r.joint + "' names frames [" +
                                  std::to_string(r.begin) + ", " + std::to_string(r.end) + "), the clip has " +
                                  std::to_string(clip.frame_count()));
        DropoutRun d;
        d.joint = *j;
        d.joint_name = r.joint;
        d.begin = r.begin;
        d.end = r.end;
        runs.push_back(d);
    }
    if (runs.empty()) return clip;
    Clip out = clip;
    repair_dropouts(out, runs);
    return out;
}

std::string describe_repairs(const std::string& clip_id, const std::vector<RepairedFrames>& repairs) {
    // Joints with the same frames together, in order of first appearance.
    std::vector<std::pair<std::pair<std::size_t, std::size_t>, std::string>> groups;
    for (const RepairedFrames& r : repairs) {
        if (r.clip != clip_id) continue;
        auto it = std::find_if(groups.begin(), groups.end(),
                               [&](const auto& g) { return g.first == std::make_pair(r.begin, r.end); });
        if (it == groups.end()) {
            groups.push_back({{r.begin, r.end}, r.joint});
        } else {
            it->second += ", " + r.joint;
        }
    }
    std::string out;
    for (const auto& g : groups)
        out += (out.empty() ? "" : "; ") + g.second + " " + frames_text(g.first.first, g.first.second);
    return out;
}

RepairSummary summarize_repairs(const std::vector<RepairedFrames>& repairs) {
    RepairSummary s;
    for (const RepairedFrames& r : repairs) {
        if (std::find(s.clips.begin(), s.clips.end(), r.clip) == s.clips.end()) s.clips.push_back(r.clip);
        s.longest_run = std::max(s.longest_run, r.end - r.begin);
    }
    return s;
}

}  // namespace mocapdb
