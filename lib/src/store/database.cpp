// Database: the read view of a motion database file.
#include "mocapdb/store/database.hpp"

#include <algorithm>
#include <functional>
#include <set>

#include "clip_codec.hpp"
#include "database_impl.hpp"
#include "h5/quiet.hpp"
#include "layout.hpp"
#include "kernel_codec.hpp"
#include "model_codec.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/store/not_found_error.hpp"
#include "packed_codec.hpp"
#include "root.hpp"
#include "set_codec.hpp"
#include "skeleton_codec.hpp"

namespace mocapdb {

using store::h5::QuietScope;

const store::h5::File& Database::Impl::f() const {
    if (file == nullptr || !file->is_open())
        throw StoreError(path.string(), "", "the database is closed (its writing session was committed)");
    return *file;
}

Database::Database(const std::filesystem::path& path) : impl_(std::make_unique<Impl>()) {
    QuietScope quiet;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw IoError(path.string() + ": no such file");
    if (!std::filesystem::is_regular_file(path, ec)) throw IoError(path.string() + ": not a regular file");
    impl_->path = path;
    impl_->reader_lock = std::make_unique<store::ReaderLock>(path);
    impl_->owned = store::h5::File::open(path, false);
    impl_->file = &impl_->owned;
    impl_->format_version = store::check_root(impl_->owned);
}

Database::Database(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Database::~Database() = default;
Database::Database(Database&&) noexcept = default;
Database& Database::operator=(Database&&) noexcept = default;

const std::filesystem::path& Database::path() const noexcept { return impl_->path; }
int Database::format_version() const noexcept { return impl_->format_version; }

std::vector<ClipRecord> Database::clips() const {
    QuietScope quiet;
    const auto& f = impl_->f();
    std::vector<ClipRecord> out;
    for (const std::string& id : f.children(store::kClips)) out.push_back(store::read_clip_record(f, id));
    return out;
}

std::size_t Database::clip_count() const {
    QuietScope quiet;
    return impl_->f().children(store::kClips).size();
}

std::optional<ClipRecord> Database::find_clip(const std::string& id) const {
    QuietScope quiet;
    if (!has_clip(id)) return std::nullopt;
    return store::read_clip_record(impl_->f(), id);
}

bool Database::has_clip(const std::string& id) const {
    QuietScope quiet;
    if (id.empty() || id.find('/') != std::string::npos || id == "." || id == "..") return false;
    return impl_->f().type_of(store::clip_path(id)) == store::h5::ObjectType::Group;
}

std::optional<std::string> Database::find_sha256(const std::string& sha256) const {
    QuietScope quiet;
    const auto& f = impl_->f();
    for (const std::string& id : f.children(store::kClips)) {
        const std::string g = store::clip_path(id);
        if (f.has_attribute(g, "source_sha256") && f.read_string_attribute(g, "source_sha256") == sha256) return id;
    }
    return std::nullopt;
}

Clip Database::load_clip(const std::string& id) const {
    QuietScope quiet;
    const auto& f = impl_->f();
    if (!has_clip(id)) throw NotFoundError(f.name(), store::clip_path(id), "no such clip");
    const ClipRecord record = store::read_clip_record(f, id);
    Clip clip;
    clip.skeleton = load_skeleton(record.skeleton);
    clip.frame_rate = record.frame_rate;
    clip.name = id;
    if (!record.lossless) {
        // Only the packed tier holds it: its channels, with the clip's stored skeleton.
        clip.channels = load_clip_packed(id).channels;
        if (clip.channels.cols() != static_cast<Eigen::Index>(clip.skeleton->channel_count()))
            throw StoreError(f.name(), store::clip_path(id),
                             "the packed tier's channels do not match the clip's skeleton");
        return clip;
    }
    clip.channels = store::read_clip_channels(f, id, clip.skeleton->channel_count());
    if (!clip.channels.allFinite())
        throw StoreError(f.name(), store::clip_channels_path(f, id), "expected finite values, found NaN or infinity");
    return clip;
}

std::optional<std::pair<std::size_t, std::size_t>> PackedTierRecord::find(const std::string& clip) const {
    for (std::size_t g = 0; g < groups.size(); ++g)
        for (std::size_t i = 0; i < groups[g].clips.size(); ++i)
            if (groups[g].clips[i].id == clip) return std::make_pair(g, i);
    return std::nullopt;
}

std::optional<PackedTierRecord> Database::packed() const {
    QuietScope quiet;
    const auto& f = impl_->f();
    if (f.type_of(store::kPacked) == store::h5::ObjectType::None) return std::nullopt;
    return store::read_packed_record(f);
}

std::shared_ptr<const packing::GroupDecoder> Database::packed_group_decoder(const std::string& group) const {
    QuietScope quiet;
    const auto& f = impl_->f();
    if (impl_->decoder_group == group && impl_->decoder) return impl_->decoder;
    store::check_link_name(group, "packed group name");
    impl_->decoder.reset();
    try {
        impl_->decoder = std::make_shared<const packing::GroupDecoder>(store::read_packed_bytes(f, group));
    } catch (const StoreError&) {
        throw;
    } catch (const Error& e) {
        throw StoreError(f.name(), store::packed_group_path(group) + "/bytes", e.what());
    }
    impl_->decoder_group = group;
    return impl_->decoder;
}

Clip Database::load_clip_packed(const std::string& id, std::size_t begin, std::size_t end) const {
    QuietScope quiet;
    const auto& f = impl_->f();
    const auto tier = packed();
    if (!tier)
        throw Refused<StoreError>(Remedy::PackFirst, f.name(), store::kPacked,
                                  "no packed tier (the database was not packed)");
    const auto where = tier->find(id);
    if (!where)
        throw NotFoundError(f.name(), store::kPacked,
                            "clip '" + id + "' is not in the packed tier (packed before it was imported?)");
    const PackedGroupRecord& g = tier->groups[where->first];
    const std::string path = store::packed_group_path(g.name) + "/bytes";
    const std::shared_ptr<const packing::GroupDecoder> decoder = packed_group_decoder(g.name);
    const std::size_t k = where->second;
    if (decoder->clip_count() != g.clips.size() || decoder->frame_count(k) != g.clips[k].frames)
        throw StoreError(
            f.name(), path,
            "the bytes hold " + std::to_string(decoder->clip_count()) + " clips, clip " + std::to_string(k) + " of " +
                std::to_string(k < decoder->clip_count() ? decoder->frame_count(k) : 0) + " frames; expected " +
                std::to_string(g.clips.size()) + " clips, clip '" + id + "' of " + std::to_string(g.clips[k].frames) +
                " frames (" + store::packed_group_path(g.name) + "/clip_frames)");
    const std::size_t frames = decoder->frame_count(k);
    if (begin >= frames)
        throw InvalidArgument("load_clip_packed: first frame " + std::to_string(begin) + " is beyond clip '" + id +
                              "' (" + std::to_string(frames) + " frames)");
    end = std::min(end, frames);
    if (end <= begin) throw InvalidArgument("load_clip_packed: empty frame range");
    Clip clip;
    try {
        clip.skeleton = decoder->skeleton(k);
        clip.frame_rate = decoder->frame_rate();
        clip.channels = decoder->decode_frames(k, begin, end);
    } catch (const Error& e) {
        throw StoreError(f.name(), path, e.what());
    }
    clip.name = id;
    return clip;
}

std::vector<std::string> Database::skeletons() const {
    QuietScope quiet;
    return impl_->f().children(store::kSkeletons);
}

std::shared_ptr<const Skeleton> Database::load_skeleton(const std::string& id) const {
    QuietScope quiet;
    const auto it = impl_->skeletons.find(id);
    if (it != impl_->skeletons.end()) return it->second;
    store::check_link_name(id, "skeleton id");
    const auto ids = skeletons();
    if (std::find(ids.begin(), ids.end(), id) == ids.end())
        throw NotFoundError(impl_->f().name(), store::skeleton_path(id), "no such skeleton");
    auto skeleton = std::make_shared<const Skeleton>(store::read_skeleton(impl_->f(), id));
    impl_->skeletons.emplace(id, skeleton);
    return skeleton;
}

std::string Database::skeleton_source(const std::string& id) const {
    QuietScope quiet;
    return impl_->f().read_string_attribute(store::skeleton_path(id), "source_file");
}

std::vector<std::string> Database::set_names() const {
    QuietScope quiet;
    return impl_->f().children(store::kSets);
}

bool Database::has_set(const std::string& name) const {
    QuietScope quiet;
    if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..") return false;
    return impl_->f().type_of(store::set_path(name)) == store::h5::ObjectType::Group;
}

std::vector<SetRecord> Database::sets() const {
    QuietScope quiet;
    const auto& f = impl_->f();
    std::vector<SetRecord> out;
    for (const std::string& name : set_names()) {
        const MotionSet set = store::read_set(f, name);
        SetRecord r;
        r.name = name;
        r.samples = set.samples.size();
        r.parameter_names = set.parameter_names;
        r.parameter_source = set.parameter_source;
        const std::string tensor = store::aligned_path(name) + "/tensor";
        if (f.type_of(store::aligned_path(name)) == store::h5::ObjectType::Group) {
            r.aligned = true;
            const auto info = f.dataset_info(tensor);
            for (std::size_t k = 0; k < 3 && k < info.shape.size(); ++k)
                r.tensor_shape[k] = static_cast<std::size_t>(info.shape[k]);
            r.tensor_stored_bytes = info.stored_bytes;
        }
        const std::string model = store::model_path(name);
        if (f.type_of(model) == store::h5::ObjectType::Group) {
            r.model = true;
            // (R3, R2, R1) in the file.
            const auto info = f.dataset_info(model + "/core");
            for (std::size_t k = 0; k < 3 && k < info.shape.size(); ++k)
                r.model_ranks[k] = static_cast<std::size_t>(info.shape[info.shape.size() - 1 - k]);
            r.model_stored_bytes = store::model_stored_bytes(f, name);
        }
        out.push_back(std::move(r));
    }
    return out;
}

MotionSet Database::load_set(const std::string& name) const {
    QuietScope quiet;
    if (!has_set(name)) throw NotFoundError(impl_->f().name(), store::set_path(name), "no such motion set");
    return store::read_set(impl_->f(), name);
}

std::optional<AlignedSet> Database::load_aligned(const std::string& set) const {
    QuietScope quiet;
    const auto& f = impl_->f();
    if (!has_set(set)) throw NotFoundError(f.name(), store::set_path(set), "no such motion set");
    if (f.type_of(store::aligned_path(set)) != store::h5::ObjectType::Group) return std::nullopt;
    return store::read_aligned(f, set);
}

std::optional<AlignedTiming> Database::load_aligned_timing(const std::string& set) const {
    QuietScope quiet;
    const auto& f = impl_->f();
    if (!has_set(set)) throw NotFoundError(f.name(), store::set_path(set), "no such motion set");
    if (f.type_of(store::aligned_path(set)) != store::h5::ObjectType::Group) return std::nullopt;
    return store::read_aligned_timing(f, set);
}

std::optional<StoredModel> Database::load_model(const std::string& set) const {
    QuietScope quiet;
    const auto& f = impl_->f();
    if (!has_set(set)) throw NotFoundError(f.name(), store::set_path(set), "no such motion set");
    const store::h5::ObjectType t = f.type_of(store::model_path(set));
    if (t == store::h5::ObjectType::None) return std::nullopt;
    if (t != store::h5::ObjectType::Group)
        throw StoreError(f.name(), store::model_path(set),
                         "expected a group of kind 'tucker_model', found another object");
    return store::read_model(f, set);
}

std::optional<synthesis::KernelFit> Database::load_kernel_fit(const std::string& set) const {
    QuietScope quiet;
    const auto& f = impl_->f();
    if (!has_set(set)) throw NotFoundError(f.name(), store::set_path(set), "no such motion set");
    if (f.type_of(store::model_path(set)) != store::h5::ObjectType::Group) return std::nullopt;
    const std::string g = store::kernel_path(set);
    const store::h5::ObjectType t = f.type_of(g);
    if (t == store::h5::ObjectType::None) return std::nullopt;
    if (t != store::h5::ObjectType::Group)
        throw StoreError(f.name(), g, "expected a group of kind 'kernel_fit', found another object");
    return store::read_kernel_fit(f, set);
}

std::uint64_t Database::file_size() const {
    QuietScope quiet;
    return store::referenced_bytes(impl_->path, store::referenced_segments(impl_->f()));
}

std::uint64_t Database::clips_file_bytes() const {
    QuietScope quiet;
    const store::h5::File& f = impl_->f();
    std::uint64_t bytes = f.object_file_bytes(store::kClips);  // the index's (or the one file's) links to the clips
    std::set<std::filesystem::path> segments;                  // other files holding clips: their /clips groups too
    const std::function<void(const std::string&)> subtree = [&](const std::string& path) {
        bytes += f.object_file_bytes(path);
        if (f.type_of(path) == store::h5::ObjectType::Group)
            for (const std::string& child : f.children(path)) subtree(path + "/" + child);
    };
    for (const std::string& id : f.children(store::kClips)) {
        const std::string g = store::clip_path(id);
        subtree(g);
        segments.insert(f.file_holding(g));
    }
    segments.erase(f.file_holding(store::kClips));
    for (const std::filesystem::path& segment : segments)
        bytes += store::h5::File::open(segment, false).object_file_bytes(store::kClips);
    return bytes;
}

std::uint64_t database_disk_bytes(const std::filesystem::path& path) { return store::disk_bytes(path); }

void copy_database(const std::filesystem::path& from, const std::filesystem::path& to) {
    QuietScope quiet;
    const Database source(from);  // checks it, and holds the readers' lock while its segments are copied
    store::copy_database(from, to);
}

}  // namespace mocapdb
