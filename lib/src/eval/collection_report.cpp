#include "mocapdb/eval/collection_report.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <system_error>

#include "mocapdb/compression/codecs/deflate.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/group_split.hpp"
#include "mocapdb/packing/measured_pack.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "mocapdb/packing/pose_index.hpp"
#include "mocapdb/store/sha256.hpp"

namespace mocapdb::eval {
namespace {

double ratio(double reference, double bytes) { return bytes > 0.0 ? reference / bytes : 0.0; }

std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

void check_options(const CollectionReportOptions& o) {
    if (o.max_error_cm.empty()) throw InvalidArgument("report: no max error given (at least one E in cm)");
    for (const double E : o.max_error_cm)
        if (!std::isfinite(E) || !(E > 0.0))
            throw InvalidArgument("report: a max error must be a finite number > 0 (cm), found " + number(E));
    if (o.threads < 1) throw InvalidArgument("report: threads must be >= 1, found " + std::to_string(o.threads));
}

// gzip's container around a raw deflate stream: 10-byte header, the file name and its NUL (gzip
// stores the name by default), CRC-32 and size (8 bytes). zlib's own wrapper is 2 + 4 bytes.
std::uint64_t gzip9_size(const std::string& text, const std::string& file_name) {
    const compression::codecs::Bytes z =
        compression::codecs::deflate_bytes(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), 9);
    return static_cast<std::uint64_t>(z.size()) - 6u + 10u + file_name.size() + 1u + 8u;
}

void measure_gzip(const std::vector<ClipRecord>& records, const std::vector<std::filesystem::path>& dirs,
                  LosslessFigures& out, const std::function<void(std::size_t, const std::string&)>& step) {
    if (dirs.empty()) {
        out.gzip_reason =
            "no source folder given (the database records each clip's file name and SHA-256, not its folder)";
        return;
    }
    // Every regular file under the folders (subfolders included), by name: folders in the order
    // given, each in sorted path order.
    std::map<std::string, std::vector<std::filesystem::path>> by_name;
    for (const auto& d : dirs) {
        std::vector<std::filesystem::path> files;
        std::error_code ec;
        for (std::filesystem::recursive_directory_iterator
                 it(d, std::filesystem::directory_options::skip_permission_denied, ec),
             end;
             !ec && it != end; it.increment(ec))
            if (it->is_regular_file(ec)) files.push_back(it->path());
        if (ec) throw IoError(d.string() + ": cannot list the folder: " + ec.message());
        std::sort(files.begin(), files.end());
        for (auto& f : files) by_name[f.filename().string()].push_back(std::move(f));
    }
    std::string first_missing, first_changed;
    std::uint64_t gzip = 0, text_bytes = 0;
    for (const ClipRecord& r : records) {
        step(r.frames, r.id);
        const auto candidates = r.source.file_name.empty() ? by_name.end() : by_name.find(r.source.file_name);
        if (candidates == by_name.end()) {
            ++out.sources_missing;
            if (first_missing.empty()) first_missing = r.source.file_name.empty() ? r.id : r.source.file_name;
            continue;
        }
        // The first file of that name with the recorded SHA-256 (several folders may hold the name).
        std::string text;
        bool same = false;
        for (const std::filesystem::path& candidate : candidates->second) {
            text = read_text_file(candidate);
            if ((same = sha256_hex(text) == r.source.sha256)) break;
        }
        if (!same) {
            ++out.sources_changed;
            if (first_changed.empty()) first_changed = candidates->second.front().string();
            continue;
        }
        ++out.sources_found;
        text_bytes += text.size();
        gzip += gzip9_size(text, r.source.file_name);
    }
    if (out.sources_missing == 0 && out.sources_changed == 0) {
        out.gzip_available = true;
        out.gzip_bytes = gzip;
        out.source_text_bytes = text_bytes;
        return;
    }
    std::string why;
    if (out.sources_missing > 0)
        why = std::to_string(out.sources_missing) + " of " + std::to_string(records.size()) +
              " source files not found in the source folders (e.g. " + first_missing + ")";
    if (out.sources_changed > 0)
        why += std::string(why.empty() ? "" : "; ") + std::to_string(out.sources_changed) +
               " source files differ from what was imported (SHA-256, e.g. " + first_changed + ")";
    out.gzip_reason = why;
}

struct PoseRef {
    std::size_t group, clip, frame;
};

}  // namespace

double PackedFigures::ratio_float32() const {
    return ratio(static_cast<double>(float32_bytes), static_cast<double>(bytes));
}
double PackedFigures::bytes_per_second() const {
    return motion_seconds > 0.0 ? static_cast<double>(bytes) / motion_seconds : 0.0;
}
double PackedFigures::bits_per_joint_frame() const {
    return joint_frames > 0.0 ? 8.0 * static_cast<double>(bytes) / joint_frames : 0.0;
}
double PackedFigures::stream_mb_per_second() const {
    return stream_seconds > 0.0 ? static_cast<double>(float32_bytes) / stream_seconds / 1e6 : 0.0;
}
double LosslessFigures::ratio_float32() const {
    return ratio(static_cast<double>(float32_bytes), static_cast<double>(bytes));
}
double LosslessFigures::gzip_ratio_float32() const {
    return gzip_available ? ratio(static_cast<double>(float32_bytes), static_cast<double>(gzip_bytes)) : 0.0;
}

double LosslessFigures::gzip_over_lossless() const {
    return bytes > 0 ? static_cast<double>(gzip_bytes) / static_cast<double>(bytes) : 0.0;
}

double CollectionReport::lossless_bytes_per_second() const {
    return motion_seconds > 0 ? static_cast<double>(lossless.bytes) / motion_seconds : 0.0;
}

CollectionReport collection_report(const Database& db, const CollectionReportOptions& options,
                                   const ProgressCallback& progress) {
    check_options(options);
    const std::vector<double>& targets = options.max_error_cm;
    const std::vector<ClipRecord> records = db.clips();
    CollectionReport out;
    out.threads = options.threads;
    out.random_poses = options.random_poses;
    out.clips = records.size();

    // Grouping from metadata and skeletons alone, as workflow::pack_database does.
    std::vector<Clip> heads(records.size());
    std::vector<const Clip*> head_ptrs;
    for (std::size_t i = 0; i < records.size(); ++i) {
        const ClipRecord& r = records[i];
        heads[i].skeleton = db.load_skeleton(r.skeleton);
        heads[i].frame_rate = r.frame_rate;
        heads[i].name = r.id;
        head_ptrs.push_back(&heads[i]);
        out.frames += r.frames;
        out.motion_seconds += static_cast<double>(r.frames) / r.frame_rate;
        out.float32_bytes += static_cast<std::uint64_t>(r.frames) * r.channels * 4u;
        out.lossless.channel_bytes += r.stored_bytes;
        const std::string stem = std::filesystem::path(r.source.file_name).stem().string();
        out.clip_names.push_back(stem.empty() ? r.id : stem);
    }
    out.lossless.float32_bytes = out.float32_bytes;
    out.lossless.bytes = db.clips_file_bytes();
    std::vector<std::vector<std::size_t>> groups;  // as workflow::pack_database groups them
    for (const std::vector<std::size_t>& g : packing::group_clips(head_ptrs)) {
        std::vector<std::size_t> frames;
        for (std::size_t i : g) frames.push_back(records[i].frames);
        for (std::vector<std::size_t>& part : packing::split_by_frames(g, frames, packing::kMaxGroupFrames))
            groups.push_back(std::move(part));
    }
    out.groups = groups.size();

    const std::uint64_t total_work =
        static_cast<std::uint64_t>(out.frames) * (targets.size() + (options.source_dirs.empty() ? 0u : 1u));
    std::uint64_t done = 0;
    auto report = [&](std::uint64_t at, std::string_view item) {
        if (progress) progress(Progress{at, total_work, item});
    };

    measure_gzip(records, options.source_dirs, out.lossless, [&](std::size_t frames, const std::string& id) {
        report(done, id);
        done += frames;
    });

    out.targets.resize(targets.size());
    std::vector<packing::ErrorAccumulator> all_errors;
    for (std::size_t t = 0; t < targets.size(); ++t) {
        out.targets[t].max_error_cm = targets[t];
        all_errors.emplace_back(targets[t]);
    }
    std::vector<std::vector<packing::GroupDecoder>> decoders(targets.size());
    for (const std::vector<std::size_t>& members : groups) {
        std::vector<Clip> clips;
        clips.reserve(members.size());
        std::uint64_t group_frames = 0, group_float32 = 0;
        double group_seconds = 0.0, group_joint_frames = 0.0;
        for (std::size_t i : members) {
            clips.push_back(db.load_clip(records[i].id));
            const Clip& c = clips.back();
            group_frames += c.frame_count();
            group_float32 += static_cast<std::uint64_t>(c.channels.size()) * 4u;
            group_seconds += static_cast<double>(c.frame_count()) / c.frame_rate;
            group_joint_frames += static_cast<double>(c.frame_count()) * static_cast<double>(c.skeleton->size());
        }
        std::vector<const Clip*> ptrs;
        std::vector<MatX> positions;
        for (const Clip& c : clips) {
            ptrs.push_back(&c);
            positions.push_back(joint_positions(c));
        }
        for (std::size_t t = 0; t < targets.size(); ++t) {
            packing::PackOptions po;
            po.max_error_cm = targets[t];
            po.threads = options.threads;
            const std::uint64_t before = done;
            ProgressCallback group_progress;
            if (progress)
                group_progress = [&](const Progress& p) {
                    const double share = p.total > 0 ? static_cast<double>(p.done) / static_cast<double>(p.total) : 0.0;
                    report(before + static_cast<std::uint64_t>(share * static_cast<double>(group_frames)), p.item);
                };
            packing::MeasuredGroup m = packing::pack_measured(ptrs, po, positions, group_progress);
            GroupFigures g;
            g.skeleton = records[members.front()].skeleton;
            g.first_clip = records[members.front()].id;
            g.frame_rate = clips.front().frame_rate;
            PackedFigures& f = g.figures;
            f.clips = clips.size();
            f.frames = group_frames;
            f.bytes = m.packed.bytes.size();
            f.float32_bytes = group_float32;
            f.motion_seconds = group_seconds;
            f.joint_frames = group_joint_frames;
            const packing::ErrorStats e = m.errors.stats();
            f.max_cm = e.max_cm;
            f.p99_cm = e.p99_cm;
            f.rmse_cm = e.rmse_cm;
            f.encode_seconds = m.encode_seconds;
            f.stream_seconds = m.decode_seconds;
            f.raw_windows = m.packed.stats.raw_windows;
            f.parts = m.packed.stats.parts;
            f.attempts = m.attempts;
            all_errors[t].merge(m.errors);
            TargetFigures& target = out.targets[t];
            PackedFigures& total = target.total;
            total.clips += f.clips;
            total.frames += f.frames;
            total.bytes += f.bytes;
            total.float32_bytes += f.float32_bytes;
            total.motion_seconds += f.motion_seconds;
            total.joint_frames += f.joint_frames;
            total.encode_seconds += f.encode_seconds;
            total.stream_seconds += f.stream_seconds;
            total.raw_windows += f.raw_windows;
            packing::add_parts(total.parts, f.parts);
            total.attempts = std::max(total.attempts, f.attempts);
            target.groups.push_back(std::move(g));
            decoders[t].emplace_back(std::move(m.packed.bytes));
            target.resident_bytes += decoders[t].back().resident_bytes();
            done = before + group_frames;
            report(done, {});
        }
    }
    for (std::size_t t = 0; t < targets.size(); ++t) {
        const packing::ErrorStats e = all_errors[t].stats();
        PackedFigures& total = out.targets[t].total;
        total.max_cm = e.max_cm;
        total.p99_cm = e.p99_cm;
        total.rmse_cm = e.rmse_cm;
    }

    // Random access: poses drawn uniformly over the collection's frames, the same ones for every E.
    if (options.random_poses > 0 && out.frames > 0) {
        std::vector<std::uint64_t> ends;  // cumulative frames in decoder order (group, clip)
        std::vector<std::pair<std::size_t, std::size_t>> where;
        std::uint64_t sum = 0;
        std::size_t channels = 0;
        for (std::size_t g = 0; g < groups.size(); ++g)
            for (std::size_t k = 0; k < groups[g].size(); ++k) {
                const ClipRecord& r = records[groups[g][k]];
                sum += r.frames;
                ends.push_back(sum);
                where.emplace_back(g, k);
                channels = std::max(channels, r.channels);
            }
        std::mt19937_64 rng(options.seed);
        std::vector<PoseRef> poses;
        poses.reserve(options.random_poses);
        for (std::size_t p = 0; p < options.random_poses; ++p) {
            const std::uint64_t u = rng() % sum;
            const std::size_t i =
                static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), u) - ends.begin());
            const std::uint64_t first = i == 0 ? 0 : ends[i - 1];
            poses.push_back({where[i].first, where[i].second, static_cast<std::size_t>(u - first)});
        }
        std::vector<double> row(channels);
        double sink = 0.0;
        for (std::size_t t = 0; t < targets.size(); ++t) {
            const auto start = std::chrono::steady_clock::now();
            for (const PoseRef& p : poses) {
                decoders[t][p.group].decode_pose(p.clip, p.frame, row.data());
                sink += row[0];
            }
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            out.targets[t].pose_microseconds = seconds / static_cast<double>(poses.size()) * 1e6;
            out.targets[t].poses_timed = poses.size();
            // Indexed: one group's index at a time (memory bounded by the largest group), its poses in
            // their random order; the index's construction is not timed.
            double indexed_seconds = 0.0;
            packing::LocalPose local;
            for (std::size_t g = 0; g < groups.size(); ++g) {
                const packing::PoseIndex index(decoders[t][g]);
                out.targets[t].index_bytes += index.memory_bytes();
                const auto begin = std::chrono::steady_clock::now();
                for (const PoseRef& p : poses)
                    if (p.group == g) {
                        index.local_pose(p.clip, p.frame, local);
                        sink += local.rotations[0].w();
                    }
                indexed_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
            }
            out.targets[t].indexed_pose_microseconds = indexed_seconds / static_cast<double>(poses.size()) * 1e6;
        }
        // Keeps the decoded values observable so the timed loop cannot be optimised away.
        volatile double observed = sink;
        (void)observed;
    }
    return out;
}

}  // namespace mocapdb::eval
