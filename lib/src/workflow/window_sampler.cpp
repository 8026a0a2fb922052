// WindowSampler: random training windows from a database's packed tier or lossless clips.
#include "mocapdb/workflow/window_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <list>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <type_traits>
#include <unordered_map>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/motion/rotation.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/pose_sampler.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/not_found_error.hpp"
#include "mocapdb/workflow/set_creation.hpp"

namespace mocapdb::workflow {
// Named, not anonymous: WindowSampler::Impl (external linkage) holds these types.
namespace window_sampler_parts {

constexpr double kTwoPi = 2.0 * kPi;

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

/// One clip decoded whole in the world frame: values (F x V, row per frame) of one element type, and per
/// frame the motion root's heading and floor position (yaw, x, z) that canonicalize a window starting there.
struct DecodedClip {
    std::vector<float> f32;
    std::vector<double> f64;
    std::vector<double> root;  ///< F x 3: yaw, x, z

    template <class T>
    std::vector<T>& values();
    template <class T>
    const std::vector<T>& values() const {
        return const_cast<DecodedClip*>(this)->values<T>();
    }
    std::size_t bytes() const { return sizeof(float) * f32.size() + sizeof(double) * (f64.size() + root.size()); }
};
template <>
std::vector<float>& DecodedClip::values<float>() {
    return f32;
}
template <>
std::vector<double>& DecodedClip::values<double>() {
    return f64;
}

}  // namespace window_sampler_parts
using namespace window_sampler_parts;

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

    // Decoded clips, least recently used first.
    std::list<std::size_t> lru;
    std::unordered_map<std::size_t, std::pair<DecodedClip, std::list<std::size_t>::iterator>> cache;
    std::size_t bytes = 0;

    packing::LocalPose local;  ///< packed: one frame's decoded local transforms
    GlobalPose pose;

    /// Decoded clip c, decoding it (and evicting the least recently used) when absent.
    const DecodedClip& decoded(std::size_t c) {
        const auto it = cache.find(c);
        if (it != cache.end()) {
            lru.splice(lru.end(), lru, it->second.second);
            return it->second.first;
        }
        DecodedClip clip = decode(c);
        while (cache.size() >= std::max(options.cache_clips, options.batch)) {
            bytes -= cache.at(lru.front()).first.bytes();
            cache.erase(lru.front());
            lru.pop_front();
        }
        lru.push_back(c);
        bytes += clip.bytes();
        auto& slot = cache[c];
        slot.first = std::move(clip);
        slot.second = std::prev(lru.end());
        return slot.first;
    }

    template <class T>
    void store(DecodedClip& out, std::size_t f, const double* row, const JointTransform& root,
               const Skeleton& s) const {
        std::vector<T>& v = out.values<T>();
        std::copy(row, row + values, v.begin() + static_cast<std::ptrdiff_t>(f * values));
        const Canonicalization c = canonicalization_of(root, s.forward());
        out.root[3 * f] = c.yaw;
        out.root[3 * f + 1] = c.translation.x();
        out.root[3 * f + 2] = c.translation.z();
    }

    void store(DecodedClip& out, std::size_t f, const double* row, const JointTransform& root,
               const Skeleton& s) const {
        if (options.dtype == WindowDType::Float32) store<float>(out, f, row, root, s);
        else store<double>(out, f, row, root, s);
    }

    void write_positions(double* row) const {
        for (std::size_t j = 0; j < pose.positions.size(); ++j)
            for (int a = 0; a < 3; ++a) row[3 * j + static_cast<std::size_t>(a)] = pose.positions[j][a];
    }

    /// The whole clip c in the world frame: pose vectors with exp-map branches continuous from its
    /// first frame (as to_pose_vectors gives them), or FK joint positions.
    DecodedClip decode(std::size_t c) {
        const SampledClip& sc = clips[c];
        DecodedClip out;
        const std::size_t frames = sc.frames;
        (options.dtype == WindowDType::Float32 ? out.f32.resize(frames * values) : out.f64.resize(frames * values));
        out.root.resize(3 * frames);
        const bool poses = options.values == WindowValues::PoseVectors;
        VecX row = VecX::Zero(static_cast<Eigen::Index>(values)), near = row;
        if (packed) {
            // Rotations straight from the decoder (never Euler angles: it holds exp maps).
            PackedGroup& g = groups[sc.group];
            const std::shared_ptr<const Skeleton> skeleton = g.decoder->skeleton(sc.index);
            const Skeleton& s = *skeleton;
            const PoseLayout layout(s);
            for (std::size_t f = 0; f < frames; ++f) {
                g.sampler->local_pose(sc.index, f, local);
                const JointTransform root = local_root_transform(s, local.rotations, local.translations);
                if (poses) {
                    pose_vector_from_local(s, layout, local.rotations, local.translations, Canonicalization{}, near,
                                           row);
                    near = row;
                } else {
                    forward_kinematics(s, local.rotations, local.translations, pose);
                    write_positions(row.data());
                }
                store(out, f, row.data(), root, s);
            }
            return out;
        }
        const Clip clip = db->load_clip(sc.id);
        const Skeleton& s = *clip.skeleton;
        const MatX world = poses ? to_pose_vectors(clip, Canonicalization{}) : MatX();
        for (std::size_t f = 0; f < frames; ++f) {
            if (poses) row = world.col(static_cast<Eigen::Index>(f));
            else {
                forward_kinematics(s, clip.frame(f), pose);
                write_positions(row.data());
            }
            store(out, f, row.data(), motion_root_transform(s, clip.frame(f)), s);
        }
        return out;
    }

    /// Window ref of a decoded clip into out (L x V), in the window's canonical frame: the first frame's
    /// root moved above the origin and turned to face +Z (pose_vector.hpp), the rigid motion applied to
    /// the cached world values. A joint whose first exp map lies off the principal branch (|v| >= pi:
    /// the clip's continuous track wound past it) is re-tracked from the principal branch, as a window
    /// decoded on its own starts.
    template <class T, class Out>
    void window_values(const DecodedClip& clip, const WindowRef& ref, Out* out) const {
        const std::size_t L = options.length, V = values;
        const T* in = clip.values<T>().data() + ref.begin * V;
        // Row of window frame f: a padded window repeats the clip's last frame.
        const std::size_t last = clips[ref.clip].frames - 1 - ref.begin;
        const auto row = [&](std::size_t f) { return in + std::min(f, last) * V; };
        const double yaw = clip.root[3 * ref.begin];
        // Pose vectors: the root's own (perhaps float-rounded) x, z, so that the window starts at exactly 0.
        const bool poses = options.values == WindowValues::PoseVectors;
        const double tx = poses ? static_cast<double>(in[0]) : clip.root[3 * ref.begin + 1];
        const double tz = poses ? static_cast<double>(in[2]) : clip.root[3 * ref.begin + 2];
        const double c = std::cos(yaw), s = std::sin(yaw);
        // R_y(-yaw) on (x, z): (c x - s z, s x + c z).
        if (!poses) {
            for (std::size_t f = 0; f < L; ++f) {
                const T* a = row(f);
                Out* b = out + f * V;
                for (std::size_t i = 0; i < V; i += 3) {
                    const double x = static_cast<double>(a[i]) - tx, z = static_cast<double>(a[i + 2]) - tz;
                    b[i] = static_cast<Out>(c * x - s * z);
                    b[i + 1] = static_cast<Out>(a[i + 1]);
                    b[i + 2] = static_cast<Out>(s * x + c * z);
                }
            }
            return;
        }
        // The heading twist psi is unwrapped along the clip; the window's first frame takes the branch in
        // [-pi, pi] (swing_twist_log's near 0) and keeps the track.
        const double psi0 = static_cast<double>(in[4]) - yaw;
        const double turn = psi0 - kTwoPi * std::round(psi0 / kTwoPi) - static_cast<double>(in[4]);
        for (std::size_t f = 0; f < L; ++f) {
            const T* a = row(f);
            Out* b = out + f * V;
            const double x = static_cast<double>(a[0]) - tx, z = static_cast<double>(a[2]) - tz;
            b[0] = static_cast<Out>(c * x - s * z);
            b[1] = static_cast<Out>(a[1]);
            b[2] = static_cast<Out>(s * x + c * z);
            const double sx = static_cast<double>(a[3]), sz = static_cast<double>(a[5]);
            b[3] = static_cast<Out>(c * sx - s * sz);
            b[4] = static_cast<Out>(static_cast<double>(a[4]) + turn);
            b[5] = static_cast<Out>(s * sx + c * sz);
            if constexpr (std::is_same_v<T, Out>) std::memcpy(b + 6, a + 6, sizeof(T) * (V - 6));
            else
                for (std::size_t i = 6; i < V; ++i) b[i] = static_cast<Out>(a[i]);
        }
        for (std::size_t r = 6; r < V; r += 3) {
            const Vec3 first(static_cast<double>(in[r]), static_cast<double>(in[r + 1]),
                             static_cast<double>(in[r + 2]));
            if (first.norm() < kPi) continue;
            Vec3 near = Vec3::Zero();
            for (std::size_t f = 0; f < L; ++f) {
                const T* a = row(f) + r;
                const Vec3 v(static_cast<double>(a[0]), static_cast<double>(a[1]), static_cast<double>(a[2]));
                near = log_map_near(exp_map(v), near);
                for (int k = 0; k < 3; ++k) out[f * V + r + static_cast<std::size_t>(k)] = static_cast<Out>(near[k]);
            }
        }
    }

    template <class Out>
    void fill(const WindowRef* refs, std::size_t count, Out* out) const {
        const std::size_t stride = options.length * values;
        for (std::size_t b = 0; b < count; ++b) {
            const auto it = cache.find(refs[b].clip);
            if (it == cache.end() || !valid(refs[b]))
                throw InvalidArgument("window sampler: fill of a window that draw() did not give");
            if (options.dtype == WindowDType::Float32)
                window_values<float>(it->second.first, refs[b], out + b * stride);
            else window_values<double>(it->second.first, refs[b], out + b * stride);
        }
    }

    /// A window of a clip: within it, or (pad) from frame 0 of a clip shorter than L.
    bool valid(const WindowRef& ref) const {
        if (ref.clip >= clips.size()) return false;
        const std::size_t frames = clips[ref.clip].frames;
        return ref.begin + options.length <= frames || (options.pad && frames < options.length && ref.begin == 0);
    }

    void check(const WindowRef& ref) const {
        if (ref.clip >= clips.size())
            throw InvalidArgument("window sampler: clip index " + std::to_string(ref.clip) + " of " +
                                  std::to_string(clips.size()));
        if (!valid(ref))
            throw InvalidArgument("window sampler: frames " + std::to_string(ref.begin) + ".." +
                                  std::to_string(ref.begin + options.length - 1) + " are beyond clip '" +
                                  clips[ref.clip].id + "' (" + std::to_string(clips[ref.clip].frames) + " frames)");
    }

    template <class Out>
    void window(const WindowRef& ref, Out* out) {
        check(ref);
        decoded(ref.clip);
        fill(&ref, 1, out);
    }
};

WindowSampler::WindowSampler(const Database& db, const WindowSamplerOptions& options)
    : impl_(std::make_unique<Impl>()) {
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
            if (!options.pad || r.frames == 0) continue;
        }
        if (first == nullptr) {
            first = &r;
            rig = db.load_skeleton(r.skeleton);
        } else {
            // Frame Time text rounds (0.0333333 s): rates within 0.01 % are one rate.
            if (std::abs(r.frame_rate - first->frame_rate) > 1e-4 * first->frame_rate)
                throw InvalidArgument(name + ": clips '" + first->id + "' (" + std::to_string(first->frame_rate) +
                                      " Hz) and '" + r.id + "' (" + std::to_string(r.frame_rate) +
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
        total += r.frames < options.length ? 1 : r.frames - options.length + 1;
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
                for (std::size_t k = 0; k < tier->groups[g].clips.size(); ++k)
                    packed_at.emplace(tier->groups[g].clips[k].id, std::make_pair(g, k));
        std::vector<std::optional<std::pair<std::size_t, std::size_t>>> where;
        bool all = tier.has_value();
        for (const SampledClip& c : m.clips) {
            const auto it = packed_at.find(c.id);
            where.push_back(it == packed_at.end() ? std::nullopt : std::make_optional(it->second));
            if (!where.back()) {
                all = false;
                if (options.source == WindowSource::Packed)
                    throw InvalidArgument(
                        name + ": clip '" + c.id + "' is not in the packed tier" +
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
                                         std::to_string(m.groups[it->second].decoder->frame_count(k)) +
                                         " frames; expected " + std::to_string(m.clips[i].frames));
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
std::vector<std::uint64_t> WindowSampler::window_counts() const {
    std::vector<std::uint64_t> out(impl_->ends.size());
    for (std::size_t c = 0; c < out.size(); ++c) out[c] = impl_->ends[c] - (c > 0 ? impl_->ends[c - 1] : 0);
    return out;
}
std::uint64_t WindowSampler::window_count() const { return impl_->ends.back(); }
double WindowSampler::frame_rate() const { return impl_->rate; }
bool WindowSampler::from_packed() const { return impl_->packed; }
const std::vector<std::string>& WindowSampler::joint_names() const { return impl_->joint_names; }

std::size_t WindowSampler::cache_bytes() const { return impl_->bytes; }

void WindowSampler::window(const WindowRef& ref, double* out) { impl_->window(ref, out); }
void WindowSampler::window(const WindowRef& ref, float* out) { impl_->window(ref, out); }

namespace {
std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}
}  // namespace

std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t epoch, std::uint64_t worker) {
    if (epoch == 0 && worker == 0) return seed;
    return splitmix64(splitmix64(splitmix64(seed) ^ epoch) ^ (worker + 0x632be59bd9b4e019ULL));
}

void WindowSampler::set_stream(std::uint64_t epoch, std::uint64_t worker) {
    impl_->rng.seed(stream_seed(impl_->options.seed, epoch, worker));
}

std::string WindowSampler::stream_state() const {
    std::ostringstream out;
    out << impl_->rng;
    return out.str();
}

void WindowSampler::set_stream_state(const std::string& state) {
    std::istringstream in(state);
    std::mt19937_64 rng;
    in >> rng;
    if (in.fail()) throw InvalidArgument("window sampler: not a stream state");
    impl_->rng = rng;
}

void WindowSampler::draw(WindowRef* refs) {
    Impl& m = *impl_;
    std::uniform_int_distribution<std::uint64_t> draw(0, m.ends.back() - 1);
    for (std::size_t b = 0; b < m.options.batch; ++b) {
        const std::uint64_t u = draw(m.rng);
        const std::size_t c =
            static_cast<std::size_t>(std::upper_bound(m.ends.begin(), m.ends.end(), u) - m.ends.begin());
        refs[b] = WindowRef{c, static_cast<std::size_t>(u - (c > 0 ? m.ends[c - 1] : 0))};
    }
    load(refs, m.options.batch);
}

void WindowSampler::load(const WindowRef* refs, std::size_t count) {
    Impl& m = *impl_;
    if (count > std::max(m.options.cache_clips, m.options.batch))
        throw InvalidArgument("window sampler: " + std::to_string(count) +
                              " windows at once; at most max(batch, cache_clips)");
    for (std::size_t b = 0; b < count; ++b) m.check(refs[b]);
    // The windows' clips are all decoded at once: the cache keeps at least that many, the most recent.
    for (std::size_t b = 0; b < count; ++b) m.decoded(refs[b].clip);
}

void WindowSampler::fill(const WindowRef* refs, std::size_t count, double* out) const { impl_->fill(refs, count, out); }
void WindowSampler::fill(const WindowRef* refs, std::size_t count, float* out) const { impl_->fill(refs, count, out); }

namespace {
template <class Out>
void next_batch(WindowSampler& s, Out* out, WindowRef* refs) {
    std::vector<WindowRef> own;
    if (refs == nullptr) {
        own.resize(s.options().batch);
        refs = own.data();
    }
    s.draw(refs);
    s.fill(refs, s.options().batch, out);
}
}  // namespace

void WindowSampler::next(double* out, WindowRef* refs) { next_batch(*this, out, refs); }
void WindowSampler::next(float* out, WindowRef* refs) { next_batch(*this, out, refs); }

}  // namespace mocapdb::workflow
