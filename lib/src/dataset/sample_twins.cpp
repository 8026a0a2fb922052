#include "mocapdb/dataset/sample_twins.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb {
namespace {

// 3 J by F joint positions of the clip in its canonical placement.
MatX canonical_positions(const Clip& clip) {
    MatX p = joint_positions(clip);
    const Canonicalization c = canonicalization_of(clip);
    for (Eigen::Index f = 0; f < p.cols(); ++f)
        for (Eigen::Index r = 0; r + 2 < p.rows(); r += 3) p.block<3, 1>(r, f) = c.apply(Vec3(p.block<3, 1>(r, f)));
    return p;
}

// Largest distance between matching joints of two 3 J vectors / matrices of the same shape.
double max_joint_distance(const Eigen::Ref<const MatX>& a, const Eigen::Ref<const MatX>& b) {
    double worst = 0.0;
    for (Eigen::Index f = 0; f < a.cols(); ++f)
        for (Eigen::Index r = 0; r + 2 < a.rows(); r += 3)
            worst = std::max(worst, (a.block<3, 1>(r, f) - b.block<3, 1>(r, f)).norm());
    return worst;
}

double mean_height(const VecX& first) {
    double sum = 0.0;
    for (Eigen::Index r = 1; r < first.size(); r += 3) sum += first(r);
    return first.size() >= 3 ? sum / static_cast<double>(first.size() / 3) : 0.0;
}

// What the sorting and the first check need of one sample: its frame count and its first frame's
// canonical joint positions (3 J values; empty when no other clip has a sample of that length).
struct Signature {
    std::size_t frames = 0;
    VecX first;
};

struct UnionFind {
    std::vector<std::size_t> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t{0}); }
    std::size_t find(std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    }
    void join(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
};

void same_clip_pairs(const MotionSet& set, const TwinOptions& o, std::vector<TwinPair>& out) {
    std::map<std::string, std::vector<std::size_t>> by_clip;
    for (std::size_t i = 0; i < set.samples.size(); ++i) by_clip[set.samples[i].clip].push_back(i);
    for (auto& [clip, idx] : by_clip) {
        std::sort(idx.begin(), idx.end(), [&](std::size_t x, std::size_t y) {
            return std::make_pair(set.samples[x].begin, x) < std::make_pair(set.samples[y].begin, y);
        });
        for (std::size_t p = 0; p < idx.size(); ++p) {
            const SampleRef& a = set.samples[idx[p]];
            for (std::size_t q = p + 1; q < idx.size() && set.samples[idx[q]].begin < a.end; ++q) {
                const SampleRef& b = set.samples[idx[q]];
                const std::size_t shared = std::min(a.end, b.end) - b.begin;
                const double shorter = static_cast<double>(std::min(a.frame_count(), b.frame_count()));
                if (shared < 2 || static_cast<double>(shared) < o.min_shared * shorter) continue;
                out.push_back({std::min(idx[p], idx[q]), std::max(idx[p], idx[q]), true, shared, 0.0});
            }
        }
    }
}

// Signatures of the samples whose frame count a sample of another clip shares (the others cannot
// have a twin in another clip and are not loaded).
std::vector<Signature> signatures(const MotionSet& set, const SampleFrames& frames) {
    const std::size_t n = set.samples.size();
    std::map<std::size_t, std::string> first_clip;  // frame count -> a clip with a sample of that length
    std::map<std::size_t, bool> shared;             // frame count -> samples of two clips have it
    for (const SampleRef& s : set.samples) {
        const auto [it, fresh] = first_clip.emplace(s.frame_count(), s.clip);
        if (!fresh && it->second != s.clip) shared[s.frame_count()] = true;
    }
    std::vector<Signature> sig(n);
    for (std::size_t i = 0; i < n; ++i) {
        sig[i].frames = set.samples[i].frame_count();
        if (!shared.count(sig[i].frames)) continue;
        const Clip sample = frames(i);
        if (sample.frame_count() != sig[i].frames)
            throw InvalidArgument("set '" + set.name + "': sample " + std::to_string(i) + " has " +
                                  std::to_string(sample.frame_count()) + " frames, its range " +
                                  std::to_string(sig[i].frames));
        sig[i].first = canonical_positions(slice(sample, 0, 1)).col(0);
    }
    return sig;
}

void other_clip_pairs(const MotionSet& set, const SampleFrames& frames, const TwinOptions& o,
                      std::vector<TwinPair>& out) {
    const std::vector<Signature> sig = signatures(set, frames);
    const std::size_t n = sig.size();
    std::vector<double> key(n);
    for (std::size_t i = 0; i < n; ++i) key[i] = mean_height(sig[i].first);
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
        return std::make_tuple(sig[x].frames, key[x], x) < std::make_tuple(sig[y].frames, key[y], y);
    });
    // Each joint within the tolerance implies mean heights within it: only neighbours in this order
    // can be twins. The first frames are compared before the whole samples are loaded.
    std::vector<std::pair<std::size_t, std::size_t>> candidates;
    for (std::size_t p = 0; p < n; ++p) {
        const std::size_t a = order[p];
        for (std::size_t q = p + 1; q < n; ++q) {
            const std::size_t b = order[q];
            if (sig[b].frames != sig[a].frames || key[b] - key[a] > o.tolerance_cm) break;
            if (set.samples[a].clip == set.samples[b].clip) continue;
            if (sig[a].first.size() == 0 || sig[a].first.size() != sig[b].first.size()) continue;
            if (max_joint_distance(sig[a].first, sig[b].first) <= o.tolerance_cm)
                candidates.emplace_back(std::min(a, b), std::max(a, b));
        }
    }
    std::sort(candidates.begin(), candidates.end());
    std::size_t loaded = n;  // the sample whose positions are in `pa` (candidates are sorted by a)
    MatX pa;
    for (const auto& [a, b] : candidates) {
        if (loaded != a) {
            pa = canonical_positions(frames(a));
            loaded = a;
        }
        const MatX pb = canonical_positions(frames(b));
        if (pb.rows() != pa.rows() || pb.cols() != pa.cols()) continue;
        const double d = max_joint_distance(pa, pb);
        if (d <= o.tolerance_cm) out.push_back({a, b, false, static_cast<std::size_t>(pa.cols()), d});
    }
}

}  // namespace

std::vector<std::vector<std::size_t>> SampleTwins::partners(std::size_t samples) const {
    std::vector<std::vector<std::size_t>> out(samples);
    for (const TwinPair& p : pairs) {
        if (p.a >= samples || p.b >= samples) throw InvalidArgument("SampleTwins::partners: index out of range");
        out[p.a].push_back(p.b);
        out[p.b].push_back(p.a);
    }
    for (auto& list : out) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
    }
    return out;
}

SampleTwins find_sample_twins(const MotionSet& set, const SampleFrames& frames, const TwinOptions& options) {
    if (!(options.tolerance_cm > 0.0) || !std::isfinite(options.tolerance_cm) || !(options.min_shared > 0.0) ||
        options.min_shared > 1.0)
        throw InvalidArgument("twin detection: the tolerance must be > 0 cm and the shared share in (0, 1]");
    SampleTwins t;
    same_clip_pairs(set, options, t.pairs);
    if (frames) other_clip_pairs(set, frames, options, t.pairs);
    std::sort(t.pairs.begin(), t.pairs.end(),
              [](const TwinPair& x, const TwinPair& y) { return std::make_pair(x.a, x.b) < std::make_pair(y.a, y.b); });
    UnionFind uf(set.samples.size());
    for (const TwinPair& p : t.pairs) uf.join(p.a, p.b);
    std::map<std::size_t, std::vector<std::size_t>> components;
    for (const TwinPair& p : t.pairs) {
        components[uf.find(p.a)].push_back(p.a);
        components[uf.find(p.b)].push_back(p.b);
    }
    for (auto& [root, members] : components) {
        std::sort(members.begin(), members.end());
        members.erase(std::unique(members.begin(), members.end()), members.end());
        t.groups.push_back(std::move(members));
    }
    std::sort(t.groups.begin(), t.groups.end());
    return t;
}

}  // namespace mocapdb
