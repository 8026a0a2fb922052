// DatabaseWriter: an atomic edit session (work on a temporary copy, publish it by rename).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>

#include "clip_codec.hpp"
#include "database_impl.hpp"
#include "h5/quiet.hpp"
#include "layout.hpp"
#include "kernel_codec.hpp"
#include "model_codec.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "packed_codec.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/store/database.hpp"
#include "root.hpp"
#include "segments.hpp"
#include "set_codec.hpp"
#include "skeleton_codec.hpp"
#include "temp_files.hpp"
#include "writer_lock.hpp"

namespace mocapdb {

using store::h5::QuietScope;

struct DatabaseWriter::Impl {
    std::unique_ptr<store::WriterLock> lock;  // held for the whole session
    std::filesystem::path target;
    std::filesystem::path temp;  // the session's index: a copy of the target's, published by rename
    store::h5::File file;        // the session's index, read through by `view`
    // The segment this session writes into (created on the first write), as links name it.
    std::string segment_name;
    std::filesystem::path segment_path;
    store::h5::File segment;
    bool segment_garbage = false;       // objects unlinked inside the session's segment: rewrite it at commit
    std::filesystem::path legacy_path;  // an older one-file target adopted as a segment (adopt_legacy_file)
    Database view{std::make_unique<Database::Impl>()};
    // Source hash -> clip id, built on first use (only sessions that add clips need it) from one
    // attribute per clip, and kept up to date by add_clip.
    std::optional<std::unordered_map<std::string, std::string>> sha_to_clip_;
    std::vector<std::pair<std::string, std::shared_ptr<const Skeleton>>> skeletons;  // id, structure
    bool finished = false;
    bool removed_links = false;             // top-level objects removed: space to reclaim in the index at commit
    bool moved = false;                     // objects copied into the session's segment (their old copies are dead)
    std::set<std::string> losing_segments;  // published segments whose objects this session dropped or moved

    std::unordered_map<std::string, std::string>& sha_to_clip() {
        if (!sha_to_clip_) {
            QuietScope quiet;
            std::unordered_map<std::string, std::string> m;
            for (const std::string& id : f().children(store::kClips))
                m.emplace(file.read_string_attribute(store::clip_path(id), "source_sha256"), id);
            sha_to_clip_ = std::move(m);
        }
        return *sha_to_clip_;
    }
    /// The session's index (what the session reads; writes go to seg()).
    store::h5::File& f() {
        if (finished) throw StoreError(target.string(), "", "the writing session is already committed");
        return file;
    }
    /// The session's segment, created on first use with the three top groups.
    store::h5::File& seg() {
        f();
        if (!segment.is_open()) {
            std::error_code ec;
            std::filesystem::create_directories(store::segment_dir(target), ec);
            if (ec)
                throw IoError(store::segment_dir(target).string() +
                              ": cannot create the segment folder: " + ec.message());
            segment_name = store::new_segment_name(target);
            segment_path = store::segment_file(target, segment_name);
            segment = store::h5::File::create(segment_path);
            segment.set_name_in_errors(target.string());
            store::write_segment_root(segment);
        }
        return segment;
    }
    bool in_session_segment(const std::string& path) {
        const auto t = f().external_target(path);
        return t && !segment_name.empty() && t->first == segment_name;
    }
    /// Remembers the published segment that top-level object `path` leaves (consolidate_segments).
    void note_loss(const std::string& path) {
        if (const auto t = f().external_target(path); t && t->first != segment_name) losing_segments.insert(t->first);
    }
    /// Points the index's top-level link `path` at the same path in the session's segment.
    void link(const std::string& path) {
        if (f().external_target(path) || file.exists(path)) file.unlink(path);
        file.link_external(path, segment_name, path);
    }
    /// Removes top-level object `path` from the index (and from the session's segment when it is there).
    void drop(const std::string& path) {
        note_loss(path);
        if (in_session_segment(path)) {
            segment.unlink(path);
            segment_garbage = true;
        }
        f().unlink(path);
        removed_links = true;
    }
    /// Makes top-level object `path` writable: a copy in the session's segment (published segments
    /// are never modified), linked from the index. Costs the object's size, once per session.
    /// `replaced`: objects below `path` the caller is about to replace or remove, not copied (a copy
    /// unlinked in the segment would be dead space that the commit rewrites the segment to drop).
    void localize(const std::string& path, const std::vector<std::string>& replaced = {}) {
        if (in_session_segment(path)) return;
        store::h5::File& out = seg();
        if (const auto t = file.external_target(path); t && t->second != path)
            throw StoreError(target.string(), path, "links to " + t->second + " (expected the same path)");
        note_loss(path);
        file.copy_to_except(out, path, replaced);
        link(path);
        moved = true;
    }
    /// Makes the target (an older, one-file database) a segment of the session's index.
    void adopt_legacy_file() {
        std::error_code ec;
        std::filesystem::create_directories(store::segment_dir(target), ec);
        if (ec)
            throw IoError(store::segment_dir(target).string() + ": cannot create the segment folder: " + ec.message());
        const std::string name = store::new_segment_name(target);
        const std::filesystem::path legacy = store::segment_file(target, name);
        std::filesystem::create_hard_link(target, legacy, ec);
        if (ec) {
            std::filesystem::copy_file(target, legacy, std::filesystem::copy_options::none, ec);
            if (ec) throw IoError(target.string() + ": cannot copy to " + legacy.string() + ": " + ec.message());
        }
        legacy_path = legacy;
        const store::h5::File old = store::h5::File::open(legacy, false);
        for (const std::string& path : store::top_level_objects(old)) file.link_external(path, name, path);
    }
    /// Keeps the segment folder small and its files few, by moving live objects into the session's
    /// segment (each move costs the object's size; published segments are never edited):
    /// - a segment that lost objects in this session and whose live datasets now hold less than half
    ///   of its bytes gives up its live objects, so that it can be removed (the dead bytes on disk
    ///   stay below the live ones in every segment);
    /// - beyond kMaxSegments segments, the smallest give up theirs until half that many are left
    ///   (sizes roughly double at each merge: each byte moves O(log n) times over n appends).
    void consolidate_segments() {
        constexpr std::size_t kMaxSegments = 32;
        std::map<std::string, std::vector<std::string>> live;  // segment -> top-level paths linked there
        for (const std::string& path : store::top_level_objects(f()))
            if (const auto t = file.external_target(path); t && t->first != segment_name)
                live[t->first].push_back(path);
        std::vector<std::string> move;
        std::vector<std::pair<std::uintmax_t, std::string>> by_size;
        for (const auto& [name, paths] : live) {
            std::error_code ec;
            const std::uintmax_t size = std::filesystem::file_size(store::segment_file(target, name), ec);
            if (losing_segments.count(name) > 0) {
                // Dataset bytes on both sides (the HDF5 metadata of many small objects would
                // otherwise count as dead).
                std::uint64_t live_bytes = 0;
                for (const std::string& path : paths) live_bytes += store::stored_bytes_under(file, path);
                std::uint64_t all_bytes = 0;
                const store::h5::File segment_file = store::h5::File::open(store::segment_file(target, name), false);
                for (const std::string& path : store::top_level_objects(segment_file))
                    all_bytes += store::stored_bytes_under(segment_file, path);
                if (2 * live_bytes < all_bytes) {
                    move.push_back(name);
                    continue;
                }
            }
            by_size.emplace_back(size, name);
        }
        if (by_size.size() > kMaxSegments) {
            std::sort(by_size.begin(), by_size.end());
            for (std::size_t i = 0; i + kMaxSegments / 2 < by_size.size(); ++i) move.push_back(by_size[i].second);
        }
        for (const std::string& name : move)
            for (const std::string& path : live[name]) localize(path);
    }
    void discard() noexcept {
        try {
            file = store::h5::File();  // closes
            segment = store::h5::File();
        } catch (...) {}
        std::error_code ec;
        std::filesystem::remove(temp, ec);
        if (!segment_path.empty()) std::filesystem::remove(segment_path, ec);
        if (!legacy_path.empty()) std::filesystem::remove(legacy_path, ec);  // a second name of the target
        // A database that was never published leaves nothing: its empty segment folder and its lock.
        if (!target.empty() && !std::filesystem::exists(target, ec)) {
            std::filesystem::remove(store::segment_dir(target), ec);  // only when empty
            if (lock) lock->remove_file();
        }
    }
};

namespace {

bool is_hex64(const std::string& s) {
    return s.size() == 64 && std::all_of(s.begin(), s.end(), [](char c) {
               return std::isdigit(static_cast<unsigned char>(c)) || (c >= 'a' && c <= 'f');
           });
}

std::string unique_name(const std::string& base, const std::function<bool(const std::string&)>& taken) {
    if (!taken(base)) return base;
    for (int k = 2;; ++k) {
        const std::string candidate = base + "-" + std::to_string(k);
        if (!taken(candidate)) return candidate;
    }
}

bool same_skeleton(const Skeleton& a, const Skeleton& b) {
    return a.same_definition(b, 1e-9) && a.position_channels() == b.position_channels() &&
           a.source_units().cm_per_unit == b.source_units().cm_per_unit &&
           a.source_units().degrees == b.source_units().degrees && (a.forward() - b.forward()).norm() <= 1e-12;
}

}  // namespace

DatabaseWriter::DatabaseWriter(const std::filesystem::path& target, Mode mode, double wait_seconds)
    : impl_(std::make_unique<Impl>()) {
    QuietScope quiet;
    Impl& s = *impl_;
    s.target = target;
    std::error_code ec;
    if (std::filesystem::exists(target, ec) && !std::filesystem::is_regular_file(target, ec))
        throw IoError(target.string() + ": exists and is not a regular file");
    // Before looking at the target: a session that waited here sees the previous session's commit.
    s.lock = std::make_unique<store::WriterLock>(target, wait_seconds);
    const bool exists = std::filesystem::exists(target, ec);
    store::remove_stale_temps(target);
    s.temp = store::make_temp_path(target);
    try {
        int version = 0;
        if (exists && mode == Mode::OpenOrCreate) {
            Database check(target);  // refuses foreign, newer, truncated files before copying
            version = check.format_version();
        }
        if (version >= 4) {
            std::filesystem::copy_file(target, s.temp, std::filesystem::copy_options::none, ec);
            if (ec) throw IoError(target.string() + ": cannot copy to " + s.temp.string() + ": " + ec.message());
            s.file = store::h5::File::open(s.temp, true);
        } else {
            s.file = store::h5::File::create(s.temp);
            store::write_root(s.file);
            // A file of an older version becomes the first segment as it is (a hard link: no copy;
            // the target's name still holds it until commit), the new index links to its objects.
            if (version > 0) s.adopt_legacy_file();
        }
        // What the session reads comes from the target's content: errors name the target.
        s.file.set_name_in_errors(target.string());
        s.view.impl_->path = s.temp;
        s.view.impl_->file = &s.file;
        for (const std::string& id : s.view.skeletons()) s.skeletons.emplace_back(id, s.view.load_skeleton(id));
    } catch (...) {
        s.discard();
        throw;
    }
}

DatabaseWriter::~DatabaseWriter() {
    if (impl_ && !impl_->finished) {
        QuietScope quiet;
        impl_->discard();
    }
}

const std::filesystem::path& DatabaseWriter::target() const noexcept { return impl_->target; }
const std::filesystem::path& DatabaseWriter::temp_path() const noexcept { return impl_->temp; }
const Database& DatabaseWriter::view() const { return impl_->view; }

std::optional<std::string> DatabaseWriter::find_sha256(const std::string& sha256) const {
    const auto& m = impl_->sha_to_clip();
    const auto it = m.find(sha256);
    if (it == m.end()) return std::nullopt;
    return it->second;
}

AddClipResult DatabaseWriter::add_clip(const Clip& clip, const ClipSource& source) {
    QuietScope quiet;
    Impl& s = *impl_;
    store::h5::File& f = s.f();
    validate(clip);
    const std::string who = "clip from '" + source.file_name + "'";
    if (clip.frame_count() == 0) throw InvalidArgument(who + ": no frames");
    if (source.file_name.empty()) throw InvalidArgument("add_clip: the source file name is empty");
    if (!is_hex64(source.sha256))
        throw InvalidArgument(who + ": sha256 must be 64 lowercase hex digits, found '" + source.sha256 + "'");
    if (source.format != "bvh" && source.format != "amc")
        throw InvalidArgument(who + ": source format must be \"bvh\" or \"amc\", found \"" + source.format + "\"");
    if (const auto it = s.sha_to_clip().find(source.sha256); it != s.sha_to_clip().end())
        return {it->second, false, "skipped: duplicate sha256 of clip " + it->second};

    const std::string stem = std::filesystem::path(source.file_name).stem().string();
    store::check_link_name(stem, "clip id");
    const std::string id = unique_name(stem, [&](const std::string& c) { return s.view.has_clip(c); });

    std::string skeleton_id;
    for (const auto& [sid, skel] : s.skeletons)
        if (same_skeleton(*skel, *clip.skeleton)) {
            skeleton_id = sid;
            break;
        }
    if (skeleton_id.empty()) {
        const std::string skeleton_file = source.skeleton_file.empty() ? source.file_name : source.skeleton_file;
        const std::string base = std::filesystem::path(skeleton_file).stem().string();
        store::check_link_name(base, "skeleton id");
        skeleton_id = unique_name(base, [&](const std::string& c) {
            return f.type_of(store::skeleton_path(c)) != store::h5::ObjectType::None;
        });
        store::write_skeleton(s.seg(), skeleton_id, *clip.skeleton, skeleton_file);
        s.link(store::skeleton_path(skeleton_id));
        s.skeletons.emplace_back(skeleton_id, clip.skeleton);
    }
    store::write_clip(s.seg(), id, clip, skeleton_id, source);
    s.link(store::clip_path(id));
    s.sha_to_clip().emplace(source.sha256, id);
    return {id, true, "added as " + id};
}

void DatabaseWriter::put_set(const MotionSet& set, bool replace) {
    QuietScope quiet;
    Impl& s = *impl_;
    store::h5::File& f = s.f();
    validate(set);
    store::check_link_name(set.name, "set name");
    const std::string who = "motion set '" + set.name + "'";
    std::string skeleton;
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
        const SampleRef& r = set.samples[i];
        const auto clip = s.view.find_clip(r.clip);
        if (!clip)
            throw InvalidArgument(who + ": sample " + std::to_string(i) + " names clip '" + r.clip +
                                  "', which is not stored");
        if (r.end > clip->frames)
            throw InvalidArgument(who + ": sample " + std::to_string(i) + " [" + std::to_string(r.begin) + ", " +
                                  std::to_string(r.end) + ") lies beyond clip '" + r.clip + "' (" +
                                  std::to_string(clip->frames) + " frames)");
        if (skeleton.empty()) skeleton = clip->skeleton;
        // Performers of one rig are stored as separate skeletons when their OFFSET lines differ;
        // they share a set when those offsets have no effect (replaced by position channels).
        if (clip->skeleton != skeleton &&
            !s.view.load_skeleton(clip->skeleton)->same_structure(*s.view.load_skeleton(skeleton)))
            throw InvalidArgument(who + ": sample " + std::to_string(i) + " (clip '" + r.clip + "') has skeleton '" +
                                  clip->skeleton + "', whose structure differs from sample 0's '" + skeleton +
                                  "' (a set's samples share one skeleton structure)");
    }
    for (const RepairedFrames& r : set.repairs) {
        const auto clip = s.view.find_clip(r.clip);
        if (!clip || r.begin >= r.end || r.end > clip->frames)
            throw InvalidArgument(
                who + ": a repair record names frames [" + std::to_string(r.begin) + ", " + std::to_string(r.end) +
                ") of clip '" + r.clip + "', which " +
                (clip ? "has " + std::to_string(clip->frames) + " frames" : std::string("is not stored")));
    }
    const std::string g = store::set_path(set.name);
    if (f.exists(g)) {
        if (!replace) throw InvalidArgument(who + " already exists (replace it explicitly)");
        s.drop(g);
    }
    store::write_set(s.seg(), set);
    s.link(g);
}

void DatabaseWriter::remove_set(const std::string& name) {
    QuietScope quiet;
    Impl& s = *impl_;
    s.f();
    if (!s.view.has_set(name)) throw StoreError(s.target.string(), store::set_path(name), "no such motion set");
    s.drop(store::set_path(name));
}

void DatabaseWriter::put_aligned(const std::string& set_name, const AlignedSet& aligned) {
    QuietScope quiet;
    Impl& s = *impl_;
    s.f();
    validate(aligned);
    if (!s.view.has_set(set_name))
        throw InvalidArgument("aligned set: motion set '" + set_name + "' is not stored (store the set first)");
    const MotionSet set = s.view.load_set(set_name);
    const std::string who = "aligned set of '" + set_name + "'";
    if (static_cast<std::size_t>(aligned.samples()) != set.samples.size())
        throw InvalidArgument(who + ": " + std::to_string(aligned.samples()) + " samples, but the set has " +
                              std::to_string(set.samples.size()));
    const auto skeleton = s.view.load_skeleton(s.view.find_clip(set.samples.front().clip)->skeleton);
    const std::size_t d = PoseLayout(*skeleton).dof_count();
    if (static_cast<std::size_t>(aligned.dofs()) != d)
        throw InvalidArgument(who + ": " + std::to_string(aligned.dofs()) +
                              " dofs, but the set's skeleton has pose vectors of " + std::to_string(d));
    for (std::size_t n = 0; n < set.samples.size(); ++n) {
        const double last = static_cast<double>(set.samples[n].frame_count() - 1);
        const auto col = aligned.warps.col(static_cast<Eigen::Index>(n));
        if (col.minCoeff() < -1e-9 || col.maxCoeff() > last + 1e-9)
            throw InvalidArgument(who + ": warps of sample " + std::to_string(n) + " leave its frames [0, " +
                                  std::to_string(set.samples[n].frame_count() - 1) + "]");
    }
    const std::string g = store::aligned_path(set_name);
    s.localize(store::set_path(set_name), {store::model_path(set_name), g});
    // A stored model described the old tensor.
    for (const std::string& old : {store::model_path(set_name), g}) {
        if (s.segment.exists(old)) {
            s.segment.unlink(old);
            s.segment_garbage = true;
        }
    }
    store::write_aligned(s.segment, set_name, aligned);
}

void DatabaseWriter::put_model(const std::string& set_name, const compression::SetModel& model,
                               const ModelFigures& figures) {
    QuietScope quiet;
    Impl& s = *impl_;
    store::h5::File& f = s.f();
    const std::string who = "model of '" + set_name + "'";
    compression::check(model, who.c_str());
    if (!s.view.has_set(set_name))
        throw InvalidArgument(who + ": motion set '" + set_name + "' is not stored (store the set first)");
    const std::string a = store::aligned_path(set_name);
    if (f.type_of(a) != store::h5::ObjectType::Group)
        throw InvalidArgument(who + ": the set is not aligned (store its aligned form first: the model describes it)");
    const store::h5::Shape shape = f.dataset_info(a + "/tensor").shape;  // (N, T, D)
    if (shape.size() != 3)
        throw StoreError(f.name(), a + "/tensor",
                         "expected 3 dimensions (sample, time, dof), found shape " + store::h5::shape_text(shape));
    const tensor::Dims3 dims = model.tucker.dims();
    const char* const names[3] = {"D (dofs)", "T (aligned frames)", "N (samples)"};
    for (int k = 0; k < 3; ++k) {
        const auto expected = static_cast<Eigen::Index>(shape.at(static_cast<std::size_t>(2 - k)));
        if (dims[static_cast<std::size_t>(k)] != expected)
            throw InvalidArgument(who + ": " + names[k] + " is " + std::to_string(dims[static_cast<std::size_t>(k)]) +
                                  ", but the aligned tensor has " + std::to_string(expected));
    }
    const tensor::TuckerModel& t = model.tucker;
    const std::pair<const char*, double> numbers[] = {{"fit", t.fit},
                                                      {"error_bound", t.error_bound},
                                                      {"data_norm", t.data_norm},
                                                      {"figures.dof_rmse", figures.dof_rmse},
                                                      {"figures.rmse_cm", figures.rmse_cm},
                                                      {"figures.mean_cm", figures.mean_cm},
                                                      {"figures.max_cm", figures.max_cm},
                                                      {"figures.p99_cm", figures.p99_cm}};
    for (const auto& [name, value] : numbers) {
        const bool may_be_negative = std::string(name) == "fit";
        if (!std::isfinite(value) || (!may_be_negative && value < 0.0))
            throw InvalidArgument(who + ": " + name + " must be finite" + (may_be_negative ? "" : " and >= 0") +
                                  ", found " + std::to_string(value));
    }
    if (t.iterations < 0)
        throw InvalidArgument(who + ": iterations must be >= 0, found " + std::to_string(t.iterations));
    const std::string g = store::model_path(set_name);
    s.localize(store::set_path(set_name), {g});
    if (s.segment.exists(g)) {
        s.segment.unlink(g);
        s.segment_garbage = true;
    }
    store::write_model(s.segment, set_name, model, figures);
}

void DatabaseWriter::put_kernel_fit(const std::string& set_name, const synthesis::KernelFit& fit) {
    QuietScope quiet;
    Impl& s = *impl_;
    store::h5::File& f = s.f();
    const std::string who = "kernel fit of '" + set_name + "'";
    if (!s.view.has_set(set_name))
        throw InvalidArgument(who + ": motion set '" + set_name + "' is not stored (store the set first)");
    if (f.type_of(store::model_path(set_name)) != store::h5::ObjectType::Group)
        throw InvalidArgument(who + ": the set has no stored model (store the model first: the kernel belongs to it)");
    store::check_kernel_fit(fit, who);
    const std::string g = store::kernel_path(set_name);
    s.localize(store::set_path(set_name), {g});
    if (s.segment.exists(g)) {
        s.segment.unlink(g);
        s.segment_garbage = true;
    }
    store::write_kernel_fit(s.segment, set_name, fit);
}

namespace {

// Refuses to replace or remove a packed tier that is the only copy of some clips.
void refuse_if_only_copy(const Database& view, const std::string& file, const std::string& action) {
    std::size_t dropped = 0;
    std::string first;
    for (const ClipRecord& r : view.clips())
        if (!r.lossless && dropped++ == 0) first = r.id;
    if (dropped > 0)
        throw StoreError(file, store::kPacked,
                         "the packed tier is the only copy of " + std::to_string(dropped) + " clip" +
                             (dropped > 1 ? "s" : "") + " (first: '" + first +
                             "'; their lossless channels were dropped); it cannot be " + action);
}

}  // namespace

void DatabaseWriter::put_packed(const PackedTierRecord& tier_in,
                                const std::vector<std::vector<std::uint8_t>>& group_bytes) {
    QuietScope quiet;
    Impl& s = *impl_;
    store::h5::File& f = s.f();
    const std::string who = "packed tier";
    if (f.exists(store::kPacked)) refuse_if_only_copy(s.view, s.target.string(), "replaced");
    if (tier_in.groups.size() != group_bytes.size())
        throw InvalidArgument(who + ": " + std::to_string(tier_in.groups.size()) + " group records but " +
                              std::to_string(group_bytes.size()) + " byte arrays");
    if (!std::isfinite(tier_in.max_error_cm) || !(tier_in.max_error_cm > 0.0))
        throw InvalidArgument(who + ": max_error_cm must be finite and > 0, found " +
                              std::to_string(tier_in.max_error_cm));
    auto check_figures = [&](const std::string& what, double max_cm, double p99_cm, double rmse_cm) {
        for (double x : {max_cm, p99_cm, rmse_cm})
            if (!std::isfinite(x) || x < 0.0)
                throw InvalidArgument(what + ": error figures must be finite and >= 0, found " + std::to_string(x));
    };
    check_figures(who, tier_in.max_cm, tier_in.p99_cm, tier_in.rmse_cm);
    PackedTierRecord tier = tier_in;
    tier.bytes = 0;
    tier.clips = 0;
    tier.frames = 0;
    std::unordered_map<std::string, std::size_t> seen;
    for (std::size_t g = 0; g < tier.groups.size(); ++g) {
        PackedGroupRecord& r = tier.groups[g];
        r.name = "g" + std::to_string(g);
        r.bytes = group_bytes[g].size();
        r.stored_bytes = 0;
        tier.bytes += r.bytes;
        const std::string gw = who + " group " + std::to_string(g);
        check_figures(gw, r.max_cm, r.p99_cm, r.rmse_cm);
        if (r.clips.empty()) throw InvalidArgument(gw + ": no clips");
        if (!s.view.load_skeleton(r.skeleton))  // StoreError when absent
            throw InvalidArgument(gw + ": no skeleton '" + r.skeleton + "'");
        std::unique_ptr<packing::GroupDecoder> decoder;
        try {
            decoder = std::make_unique<packing::GroupDecoder>(group_bytes[g]);
        } catch (const Error& e) {
            throw InvalidArgument(gw + ": the bytes do not parse: " + e.what());
        }
        if (decoder->clip_count() != r.clips.size() || decoder->frame_rate() != r.frame_rate)
            throw InvalidArgument(gw + ": the bytes hold " + std::to_string(decoder->clip_count()) + " clips at " +
                                  std::to_string(decoder->frame_rate()) + " Hz, the record " +
                                  std::to_string(r.clips.size()) + " at " + std::to_string(r.frame_rate) + " Hz");
        for (std::size_t i = 0; i < r.clips.size(); ++i) {
            const PackedClipRecord& c = r.clips[i];
            const auto record = s.view.find_clip(c.id);
            if (!record) throw InvalidArgument(gw + ": clip '" + c.id + "' is not stored");
            if (!seen.emplace(c.id, g).second) throw InvalidArgument(who + ": clip '" + c.id + "' appears twice");
            if (record->frames != c.frames || decoder->frame_count(i) != c.frames)
                throw InvalidArgument(gw + ": clip '" + c.id + "' has " + std::to_string(record->frames) +
                                      " frames stored, " + std::to_string(c.frames) + " in the record and " +
                                      std::to_string(decoder->frame_count(i)) + " in the bytes");
            check_figures(gw + " clip '" + c.id + "'", c.max_cm, c.p99_cm, c.rmse_cm);
        }
        r.frames = 0;
        for (const PackedClipRecord& c : r.clips) r.frames += c.frames;
        tier.clips += r.clips.size();
        tier.frames += r.frames;
    }
    if (f.exists(store::kPacked)) s.drop(store::kPacked);
    store::write_packed(s.seg(), tier, group_bytes);
    s.link(store::kPacked);
    s.view.impl_->decoder.reset();
}

void DatabaseWriter::remove_packed() {
    QuietScope quiet;
    Impl& s = *impl_;
    store::h5::File& f = s.f();
    if (!f.exists(store::kPacked)) throw StoreError(s.target.string(), store::kPacked, "no packed tier");
    refuse_if_only_copy(s.view, s.target.string(), "removed");
    s.view.impl_->decoder.reset();
    s.drop(store::kPacked);
}

std::size_t DatabaseWriter::drop_lossless() {
    QuietScope quiet;
    Impl& s = *impl_;
    store::h5::File& f = s.f();
    const std::optional<PackedTierRecord> tier = s.view.packed();
    if (!tier)
        throw StoreError(
            s.target.string(), store::kPacked,
            "no packed tier: the lossless channels are the only copy of the clips (run mocapdb pack first)");
    std::size_t dropped = 0;
    for (const PackedGroupRecord& g : tier->groups)
        for (const PackedClipRecord& c : g.clips) {
            if (!store::read_clip_record(f, c.id).lossless) continue;
            s.localize(store::clip_path(c.id));
            store::drop_lossless_channels(s.segment, c.id);
            s.segment_garbage = true;
            ++dropped;
        }
    return dropped;
}

void DatabaseWriter::commit() {
    QuietScope quiet;
    Impl& s = *impl_;
    s.f();
    try {
        s.consolidate_segments();
        s.view.impl_->skeletons.clear();
        s.view.impl_->decoder.reset();
        s.file.close();  // also closes the segments it opened through links
        if (s.segment.is_open()) {
            s.segment.close();
            // HDF5 does not reuse the space of objects unlinked in this session's segment: copy what
            // is live into a new file of the same name (nothing links to it before the index is published).
            if (s.segment_garbage) store::rewrite_live_objects(s.segment_path);
            store::make_durable(s.segment_path);
        }
        if (s.removed_links || s.moved) store::rewrite_live_objects(s.temp);
        store::publish(s.temp, s.target);
        s.finished = true;
        s.segment_path.clear();  // published: no longer the session's to remove
        s.legacy_path.clear();
        try {
            std::set<std::string> referenced;
            {
                const store::h5::File published = store::h5::File::open(s.target, false);
                referenced = store::referenced_segments(published);
            }
            store::remove_unreferenced_segments(s.target, referenced);
        } catch (const std::exception&) {
            // Published; unreferenced segments stay until a later commit removes them.
        }
        s.lock.reset();  // the next session may start from the published file
    } catch (...) {
        if (!s.finished) s.discard();
        s.finished = true;
        s.lock.reset();
        throw;
    }
}

}  // namespace mocapdb
