// WindowSampler: random training windows from a database's packed tier or lossless clips.
#include "mocapdb/workflow/window_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <list>
#include <map>
#include <optional>
#include <random>
#include <unordered_map>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/pose_sampler.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/not_found_error.hpp"
#include "mocapdb/workflow/set_creation.hpp"

namespace mocapdb::workflow {
namespace {

/// Windows of one rig give arrays of one shape and meaning: same joints, parents and pose layout.
bool same_rig(const Skeleton& a, const Skeleton& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t j = 0; j < a.size(); ++j) {
        const Joint &x = a.joint(j), &y = b.joint(j);
        if (x.name != y.name || x.parent != y.parent || x.end_site != y.end_site) return false;
    }
    return PoseLayout(a).rotation_joints() == PoseLayout(b).rotation_joints();
}

std::string rig_text(const ClipRecord& r, const Skeleton& s) {
    return "'" + r.id + "' (skeleton " + r.skeleton + ", " + std::to_string(s.size()) + " joints, " +
           std::to_string(PoseLayout(s).dof_count()) + " pose values)";
}

struct SampledClip {
    std::string id;
    std::size_t frames = 0;
    std::size_t group = 0;  ///< packed: index into Impl::groups
    std::size_t index = 0;  ///< packed: the clip's index in its group
};

struct PackedGroup {
    std::shared_ptr<const packing::GroupDecoder> decoder;
    std::unique_ptr<packing::PoseSampler> sampler;
};

}  // namespace

struct WindowSampler::Impl {
    const Database* db = nullptr;
    WindowSamplerOptions options;
    std::vector<SampledClip> clips;
    std::vector<std::string> ids;
    std::vector<std::string> short_ids;
    std::vector<std::uint64_t> ends;  ///< running totals of the clips' window counts
    double rate = 0.0;
    bool packed = false;
    std::size_t values = 0;
    std::vector<std::string> joint_names;
    std::vector<PackedGroup> groups;
    std::mt19937_64 rng;

    // Lossless clips, least recently used first.
    std::list<std::size_t> lru;
    std::unordered_map<std::size_t, std::pair<Clip, std::list<std::size_t>::iterator>> cache;

    Clip window_clip;  ///< lossless: the window's rows (L x channels) with its skeleton and rate
    packing::LocalPose local;  ///< packed: one frame's decoded local transforms
    VecX near;                 ///< the previous frame's pose vector (exp-map branches)
    GlobalPose pose;

    const Clip& lossless(std::size_t c) {
        const auto it = cache.find(c);
        if (it != cache.end()) {
            lru.splice(lru.end(), lru, it->second.second);
            return it->second.first;
        }
        if (cache.size() >= std::max<std::size_t>(options.cache_clips, 1)) {
            cache.erase(lru.front());
            lru.pop_front();
        }
        lru.push_back(c);
        auto& slot = cache[c];
        slot.first = db->load_clip(clips[c].id);
        slot.second = std::prev(lru.end());
        return slot.first;
    }

    /// Fills window_clip with the lossless rows of the window.
    void load_rows(const WindowRef& ref) {
        const Clip& clip = lossless(ref.clip);
        window_clip.skeleton = clip.skeleton;
        window_clip.channels =
            clip.channels.middleRows(static_cast<Eigen::Index>(ref.begin), static_cast<Eigen::Index>(options.length));
        window_clip.frame_rate = rate;
    }

    /// Writes one frame's values from its global pose (joint positions) in the window's frame.
    void write_positions(const Canonicalization& canonical, double* row) const {
        for (std::size_t j = 0; j < pose.positions.size(); ++j) {
            const Vec3 p = canonical.apply(pose.positions[j]);
            row[3 * j] = p.x();
            row[3 * j + 1] = p.y();
            row[3 * j + 2] = p.z();
        }
    }

    /// A packed window straight from the decoded local transforms (rotations, never Euler angles:
    /// the decoder holds exp maps, and channels would cost a conversion each way).
    void packed_window(const WindowRef& ref, double* out) {
        const SampledClip& c = clips[ref.clip];
        PackedGroup& g = groups[c.group];
        const std::shared_ptr<const Skeleton> skeleton = g.decoder->skeleton(c.index);
        const Skeleton& s = *skeleton;
        const bool poses = options.values == WindowValues::PoseVectors;
        const PoseLayout layout(s);
        Canonicalization canonical;
        near.setZero(static_cast<Eigen::Index>(values));
        for (std::size_t f = 0; f < options.length; ++f) {
            g.sampler->local_pose(c.index, ref.begin + f, local);
            if (f == 0) canonical = canonicalization_of(local_root_transform(s, local.rotations, local.translations), s.forward());
            double* row = out + f * values;
            if (poses) {
                Eigen::Map<VecX> column(row, static_cast<Eigen::Index>(values));
                pose_vector_from_local(s, layout, local.rotations, local.translations, canonical, near, column);
                near = column;
            } else {
                forward_kinematics(s, local.rotations, local.translations, pose);
                write_positions(canonical, row);
            }
        }
    }

    void lossless_window(const WindowRef& ref, double* out) {
        load_rows(ref);
        const Canonicalization canonical = canonicalization_of(window_clip);
        if (options.values == WindowValues::PoseVectors) {
            // D x L column-major is L x D row-major: the layout of out.
            const MatX poses = to_pose_vectors(window_clip, canonical);
            std::memcpy(out, poses.data(), sizeof(double) * options.length * values);
            return;
        }
        for (std::size_t f = 0; f < options.length; ++f) {
            forward_kinematics(*window_clip.skeleton, window_clip.frame(f), pose);
            write_positions(canonical, out + f * values);
        }
    }
};

WindowSampler::WindowSampler(const Database& db, const WindowSamplerOptions& options) : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.db = &db;
    m.options = options;
    m.rng.seed(options.seed);
    const std::string name = db.path().string();
    if (options.length == 0) throw InvalidArgument("window sampler: the window length must be at least 1 frame");
    if (options.batch == 0) throw InvalidArgument("window sampler: the batch size must be at least 1 window");

    std::map<std::string, ClipRecord> records;
    for (ClipRecord& r : db.clips()) records.emplace(r.id, std::move(r));
    if (records.empty()) throw InvalidArgument(name + ": the database holds no clips; import some first");
    std::vector<std::string> selected;
    if (options.clips.empty())
        for (const auto& [id, r] : records) selected.push_back(id);
    else {
        for (const std::string& p : options.clips)
            if (p.find_first_of("*?[") == std::string::npos && records.count(p) == 0)
                throw NotFoundError(name, "/clips/" + p, "no such clip");
        selected = select_clips(db, name, options.clips);
    }

    // One rig and one frame rate, so that every batch is one array of one meaning.
    const ClipRecord* first = nullptr;
    std::shared_ptr<const Skeleton> rig;
    std::map<std::string, bool> rig_checked;
    std::uint64_t total = 0;
    for (const std::string& id : selected) {
        const ClipRecord& r = records.at(id);
        if (r.frames < options.length) {
            m.short_ids.push_back(id);
            continue;
        }
        if (first == nullptr) {
            first = &r;
            rig = db.load_skeleton(r.skeleton);
        } else {
            // Frame Time text rounds (0.0333333 s): rates within 0.01 % are one rate.
            if (std::abs(r.frame_rate - first->frame_rate) > 1e-4 * first->frame_rate)
                throw InvalidArgument(name + ": clips '" + first->id + "' (" + std::to_string(first->frame_rate) + " Hz) and '" +
                                      r.id + "' (" + std::to_string(r.frame_rate) +
                                      " Hz) differ in frame rate; select clips of one rate (clip patterns)");
            auto [it, fresh] = rig_checked.emplace(r.skeleton, false);
            if (fresh) it->second = same_rig(*rig, *db.load_skeleton(r.skeleton));
            if (!it->second)
                throw InvalidArgument(name + ": clips " + rig_text(*first, *rig) + " and " +
                                      rig_text(r, *db.load_skeleton(r.skeleton)) +
                                      " are of different rigs; select clips of one rig (clip patterns)");
        }
        m.clips.push_back({id, r.frames, 0, 0});
        m.ids.push_back(id);
        total += r.frames - options.length + 1;
        m.ends.push_back(total);
    }
    if (m.clips.empty())
        throw InvalidArgument(name + ": none of the " + std::to_string(selected.size()) + " selected clips has " +
                              std::to_string(options.length) + " frames (a window's length)");
    m.rate = first->frame_rate;
    for (const Joint& j : rig->joints()) m.joint_names.push_back(j.name);
    m.values = options.values == WindowValues::PoseVectors ? PoseLayout(*rig).dof_count() : 3 * rig->size();

    // The packed tier, when asked for or when it holds every selected clip.
    if (options.source != WindowSource::Lossless) {
        const auto tier = db.packed();
        std::map<std::string, std::pair<std::size_t, std::size_t>> packed_at;  // clip -> (group, index)
        if (tier)
            for (std::size_t g = 0; g < tier->groups.size(); ++g)
                for (std::size_t k = 0; k < tier->groups[g].clips.size(); ++k) packed_at.emplace(tier->groups[g].clips[k].id, std::make_pair(g, k));
        std::vector<std::optional<std::pair<std::size_t, std::size_t>>> where;
        bool all = tier.has_value();
        for (const SampledClip& c : m.clips) {
            const auto it = packed_at.find(c.id);
            where.push_back(it == packed_at.end() ? std::nullopt : std::make_optional(it->second));
            if (!where.back()) {
                all = false;
                if (options.source == WindowSource::Packed)
                    throw InvalidArgument(name + ": clip '" + c.id + "' is not in the packed tier" +
                                          (tier ? " (imported after `mocapdb pack`?)" : " (the database has none: mocapdb pack)"));
            }
        }
        if (all) {
            m.packed = true;
            std::map<std::size_t, std::size_t> group_of;  // tier group -> index into m.groups
            for (std::size_t i = 0; i < m.clips.size(); ++i) {
                const auto [g, k] = *where[i];
                auto [it, fresh] = group_of.emplace(g, m.groups.size());
                if (fresh) {
                    PackedGroup pg;
                    pg.decoder = db.packed_group_decoder(tier->groups[g].name);
                    // A window spans L / W + 2 packed windows at most; keep a few windows' worth decoded.
                    const std::size_t span = options.length / std::max<std::size_t>(pg.decoder->window_length(), 1) + 2;
                    pg.sampler = std::make_unique<packing::PoseSampler>(*pg.decoder, 2 * span);
                    m.groups.push_back(std::move(pg));
                }
                m.clips[i].group = it->second;
                m.clips[i].index = k;
                if (m.groups[it->second].decoder->frame_count(k) != m.clips[i].frames)
                    throw StoreError(name, "/packed/" + tier->groups[g].name,
                                     "the packed clip '" + m.clips[i].id + "' has " +
                                         std::to_string(m.groups[it->second].decoder->frame_count(k)) + " frames; expected " +
                                         std::to_string(m.clips[i].frames));
            }
        }
    }
}

WindowSampler::~WindowSampler() = default;
WindowSampler::WindowSampler(WindowSampler&&) noexcept = default;
WindowSampler& WindowSampler::operator=(WindowSampler&&) noexcept = default;

const WindowSamplerOptions& WindowSampler::options() const { return impl_->options; }
std::size_t WindowSampler::values_per_frame() const { return impl_->values; }
const std::vector<std::string>& WindowSampler::clip_ids() const { return impl_->ids; }
const std::vector<std::string>& WindowSampler::short_clip_ids() const { return impl_->short_ids; }
std::uint64_t WindowSampler::window_count() const { return impl_->ends.back(); }
double WindowSampler::frame_rate() const { return impl_->rate; }
bool WindowSampler::from_packed() const { return impl_->packed; }
const std::vector<std::string>& WindowSampler::joint_names() const { return impl_->joint_names; }

void WindowSampler::window(const WindowRef& ref, double* out) {
    Impl& m = *impl_;
    if (ref.clip >= m.clips.size())
        throw InvalidArgument("window sampler: clip index " + std::to_string(ref.clip) + " of " + std::to_string(m.clips.size()));
    if (ref.begin + m.options.length > m.clips[ref.clip].frames)
        throw InvalidArgument("window sampler: frames " + std::to_string(ref.begin) + ".." +
                              std::to_string(ref.begin + m.options.length - 1) + " are beyond clip '" + m.clips[ref.clip].id +
                              "' (" + std::to_string(m.clips[ref.clip].frames) + " frames)");
    if (m.packed)
        m.packed_window(ref, out);
    else
        m.lossless_window(ref, out);
}

void WindowSampler::next(double* out, WindowRef* refs) {
    Impl& m = *impl_;
    std::uniform_int_distribution<std::uint64_t> draw(0, m.ends.back() - 1);
    const std::size_t stride = m.options.length * m.values;
    for (std::size_t b = 0; b < m.options.batch; ++b) {
        const std::uint64_t u = draw(m.rng);
        const std::size_t c = static_cast<std::size_t>(std::upper_bound(m.ends.begin(), m.ends.end(), u) - m.ends.begin());
        const WindowRef ref{c, static_cast<std::size_t>(u - (c > 0 ? m.ends[c - 1] : 0))};
        window(ref, out + b * stride);
        if (refs != nullptr) refs[b] = ref;
    }
}

}  // namespace mocapdb::workflow
