// ACL's own decoder beside ours in one run (issue 36 item 3): every clip of a shared folder compressed
// by ACL (headers from MOCAPDB_ACL_DIR, benchmarks/CMakeLists.txt) and packed by mocapdb at the same E;
// per codec its bytes, its max error with our metric and the time of one cold random whole pose.
//
//   bench_acl_runtime [--folder cmu-walkrun-pfnn|cmu-asfamc|all] [--errors 1,0.5,0.1] [--poses 20000]
//                     [--repeats 5] [--seed 7] [--limit N] [--threads 2] [--cache DIR] [--index] [--json]
//
// ACL as ../shared/reference/acl/README.md made its tables: one transform track per joint and end site
// (local rotation and translation = Skeleton::local_rotation / local_translation of the source row,
// the transforms packing::LocalPose holds; scale 1), sample rate = clip rate (BVH read at 60 Hz),
// get_default_compression_settings(), per-track precision E cm, ACL's recommended lossy pre-processing.
// Ours: packing::pack_measured per group as `mocapdb pack` groups them, GroupDecoder::decode_local_pose.
// Error: FK of every joint and end site of the decoded local transforms at every source frame against
// FK of the source clip (cm). Timing: N (clip, frame) drawn uniformly over the folder's frames
// (mt19937_64, --seed), the same sequence for every codec; one thread; per repeat every codec runs the
// sequence once (in turn); µs per pose from thread CPU time and wall time, min and median of repeats.
// Codecs: `acl` (one decompression context, initialized for each pose: nothing kept between poses),
// `acl_ctx` (a context per clip, initialized before timing; which of the two is faster changes between
// runs, by up to ~15 %; ACL seeks frame / rate, rounding to the nearest sample); `packed` (ours); with
// --index `index` (a PoseIndex per group: the packed tier expanded in memory; bytes = packed + index
// memory). More go into make_codecs() (a PoseCodec each). Columns: `us/ACL` thread CPU min over the
// faster ACL variant's; `ACL/bytes` ACL's bytes at the same E over the codec's; `x ACL @max`
// compare.py's figure (ACL's bytes from its table, interpolated at the codec's measured max).
// --limit N: the first N clips in name order. --cache DIR keeps ACL's and our bytes per (folder,
// clips, E) between runs; delete it when a codec or the data change.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <acl/compression/compress.h>
#include <acl/compression/pre_process.h>
#include <acl/compression/track_array.h>
#include <acl/compression/transform_error_metrics.h>
#include <acl/core/ansi_allocator.h>
#include <acl/decompression/decompress.h>
#include <nlohmann/json.hpp>

#include "bench_timing.hpp"
#include "shared_folder.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/core/parallel_tasks.hpp"
#include "mocapdb/eval/acl_reference.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/error_stats.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/group_split.hpp"
#include "mocapdb/packing/measured_pack.hpp"
#include "mocapdb/packing/pose_index.hpp"

namespace fs = std::filesystem;
using namespace mocapdb;
using namespace mocapdb::bench;

namespace {

/// A decoder timed here. `clip` indexes the folder's clips in name order.
struct PoseCodec {
    std::string name;
    std::uint64_t bytes = 0;  ///< everything it decodes from
    /// Timed: one whole pose (every joint's local transform) into the codec's own output; returns a
    /// value of that output (kept observable so the work is not optimized away).
    std::function<double(std::size_t clip, std::size_t frame)> decode;
    /// Untimed, for the error: the same pose as local transforms in skeleton joint order.
    std::function<void(std::size_t clip, std::size_t frame, packing::LocalPose& out)> local_pose;
};

// ---- byte cache: one file of blobs per (folder, clips, E, codec) ----

using Blobs = std::vector<std::vector<std::uint8_t>>;

fs::path cache_file(const std::string& dir, const std::string& folder, std::size_t clips, double E, const char* codec) {
    std::ostringstream name;
    name << folder << "_n" << clips << "_E" << E << "_" << codec << ".blobs";
    return fs::path(dir) / name.str();
}

bool read_blobs(const fs::path& file, Blobs& out) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return false;
    std::uint64_t count = 0;
    if (!in.read(reinterpret_cast<char*>(&count), sizeof count) || count > (1u << 20)) return false;
    out.assign(count, {});
    for (auto& b : out) {
        std::uint64_t size = 0;
        if (!in.read(reinterpret_cast<char*>(&size), sizeof size) || size > (std::uint64_t{1} << 32)) return false;
        b.resize(size);
        if (!in.read(reinterpret_cast<char*>(b.data()), static_cast<std::streamsize>(size))) return false;
    }
    return true;
}

void write_blobs(const fs::path& file, const Blobs& blobs) {
    fs::create_directories(file.parent_path());
    const fs::path tmp = file.string() + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        const std::uint64_t count = blobs.size();
        out.write(reinterpret_cast<const char*>(&count), sizeof count);
        for (const auto& b : blobs) {
            const std::uint64_t size = b.size();
            out.write(reinterpret_cast<const char*>(&size), sizeof size);
            out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(size));
        }
    }
    fs::rename(tmp, file);
}

// ---- ACL ----

/// Every clip compressed by ACL: the buffers (16-byte aligned, owned) and the decoders' state.
class AclClips {
public:
    AclClips() = default;
    AclClips(const AclClips&) = delete;
    AclClips& operator=(const AclClips&) = delete;
    ~AclClips() {
        for (acl::compressed_tracks* t : tracks_)
            if (t != nullptr) allocator_.deallocate(t, t->get_size());  // nullptr: compression threw
    }

    /// Compresses every clip at precision E cm (threads: clips in parallel).
    void compress(const std::vector<Clip>& clips, double E) {
        tracks_.assign(clips.size(), nullptr);
        run_parallel_tasks(clips.size(), [&](std::size_t k) { tracks_[k] = compress_clip(clips[k], E); });
        bind();
    }

    /// Adopts buffers written by blobs(); false when one is not a valid ACL buffer.
    bool adopt(const Blobs& blobs) {
        for (const auto& b : blobs) {
            void* p = allocator_.allocate(b.size(), 16);
            std::copy(b.begin(), b.end(), static_cast<std::uint8_t*>(p));
            acl::compressed_tracks* t = acl::make_compressed_tracks(p);
            if (t == nullptr || t->is_valid(true).any()) {
                allocator_.deallocate(p, b.size());
                return false;
            }
            tracks_.push_back(t);
        }
        bind();
        return true;
    }

    Blobs blobs() const {
        Blobs out;
        for (const acl::compressed_tracks* t : tracks_) {
            const auto* p = reinterpret_cast<const std::uint8_t*>(t);
            out.emplace_back(p, p + t->get_size());
        }
        return out;
    }

    std::uint64_t bytes() const {
        std::uint64_t sum = 0;
        for (const acl::compressed_tracks* t : tracks_) sum += t->get_size();
        return sum;
    }

    /// One pose with the clip's own context (initialized in bind()).
    double decode_bound(std::size_t clip, std::size_t frame) {
        Context& c = *contexts_[clip];
        c.seek(static_cast<float>(frame) / rates_[clip], acl::sample_rounding_policy::nearest);
        c.decompress_tracks(writer_);
        return rtm::quat_get_w(writer_.rotations[1].v) + rtm::vector_get_x(writer_.translations[0].v);
    }

    /// One pose with one context, initialized for this pose (nothing kept between poses).
    double decode(std::size_t clip, std::size_t frame) {
        shared_.initialize(*tracks_[clip]);
        shared_.seek(static_cast<float>(frame) / rates_[clip], acl::sample_rounding_policy::nearest);
        shared_.decompress_tracks(writer_);
        return rtm::quat_get_w(writer_.rotations[1].v) + rtm::vector_get_x(writer_.translations[0].v);
    }

    /// The pose decode() (or, `bound`, decode_bound()) gives, as doubles.
    void local_pose(std::size_t clip, std::size_t frame, bool bound, packing::LocalPose& out) {
        if (bound) decode_bound(clip, frame);
        else decode(clip, frame);
        const std::size_t n = tracks_[clip]->get_num_tracks();
        out.rotations.resize(n);
        out.translations.resize(n);
        for (std::size_t j = 0; j < n; ++j) {
            const rtm::quatf q = writer_.rotations[j].v;
            const rtm::vector4f t = writer_.translations[j].v;
            out.rotations[j] = Quat(rtm::quat_get_w(q), rtm::quat_get_x(q), rtm::quat_get_y(q), rtm::quat_get_z(q));
            out.translations[j] = Vec3(rtm::vector_get_x(t), rtm::vector_get_y(t), rtm::vector_get_z(t));
        }
    }

private:
    using Context = acl::decompression_context<acl::default_transform_decompression_settings>;

    /// ACL's output: rtm values as a runtime keeps them (wrapped: std::vector drops a SIMD type's attributes).
    struct Q {
        rtm::quatf v;
    };
    struct V {
        rtm::vector4f v;
    };
    struct Writer final : acl::track_writer {
        std::vector<Q> rotations;
        std::vector<V> translations, scales;
        void RTM_SIMD_CALL write_rotation(std::uint32_t i, rtm::quatf_arg0 q) { rotations[i].v = q; }
        void RTM_SIMD_CALL write_translation(std::uint32_t i, rtm::vector4f_arg0 t) { translations[i].v = t; }
        void RTM_SIMD_CALL write_scale(std::uint32_t i, rtm::vector4f_arg0 s) { scales[i].v = s; }
    };

    acl::compressed_tracks* compress_clip(const Clip& clip, double E) {
        const Skeleton& skeleton = *clip.skeleton;
        const auto joints = static_cast<std::uint32_t>(skeleton.size());
        const auto frames = static_cast<std::uint32_t>(clip.frame_count());
        const auto rate = static_cast<float>(clip.frame_rate);
        acl::track_array_qvvf tracks(allocator_, joints);
        for (std::uint32_t j = 0; j < joints; ++j) {
            acl::track_desc_transformf desc;
            desc.output_index = j;
            const int parent = skeleton.joint(j).parent;
            desc.parent_index = parent < 0 ? acl::k_invalid_track_index : static_cast<std::uint32_t>(parent);
            desc.precision = static_cast<float>(E);
            acl::track_qvvf track = acl::track_qvvf::make_reserve(desc, allocator_, frames, rate);
            for (std::uint32_t f = 0; f < frames; ++f) {
                const double* row = clip.frame(f);
                const Quat q = skeleton.local_rotation(j, row);
                const Vec3 t = skeleton.local_translation(j, row);
                track[f] = rtm::qvv_set(
                    rtm::quat_set(static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()),
                                  static_cast<float>(q.w())),
                    rtm::vector_set(static_cast<float>(t.x()), static_cast<float>(t.y()), static_cast<float>(t.z())),
                    rtm::vector_set(1.0F));
            }
            tracks[j] = std::move(track);
        }
        acl::qvvf_transform_error_metric metric;
        acl::pre_process_settings_t pre;
        pre.actions = acl::pre_process_actions::recommended;
        pre.precision_policy = acl::pre_process_precision_policy::lossy;
        pre.error_metric = &metric;
        acl::error_result r = acl::pre_process_track_list(allocator_, pre, tracks);
        if (r.any()) throw Error("ACL pre-processing of " + clip.name + ": " + r.c_str());
        acl::compression_settings settings = acl::get_default_compression_settings();
        settings.error_metric = &metric;
        acl::output_stats stats;
        acl::compressed_tracks* out = nullptr;
        r = acl::compress_track_list(allocator_, tracks, settings, out, stats);
        if (r.any()) throw Error("ACL compression of " + clip.name + ": " + r.c_str());
        return out;
    }

    void bind() {
        std::size_t joints = 0;
        contexts_.clear();
        rates_.clear();
        for (const acl::compressed_tracks* t : tracks_) {
            joints = std::max<std::size_t>(joints, t->get_num_tracks());
            contexts_.push_back(std::make_unique<Context>());
            if (!contexts_.back()->initialize(*t)) throw Error("ACL: a decompression context does not initialize");
            rates_.push_back(t->get_sample_rate());
        }
        writer_.rotations.assign(joints, Q{rtm::quat_identity()});
        writer_.translations.assign(joints, V{rtm::vector_zero()});
        writer_.scales.assign(joints, V{rtm::vector_set(1.0F)});
    }

    acl::ansi_allocator allocator_;
    std::vector<acl::compressed_tracks*> tracks_;
    std::vector<std::unique_ptr<Context>> contexts_;
    std::vector<float> rates_;
    Context shared_;
    Writer writer_;
};

// ---- ours ----

/// The folder packed as `mocapdb pack` groups it; clip k is member where[k].second of group where[k].first.
struct PackedClips {
    std::vector<packing::GroupDecoder> groups;
    std::vector<std::pair<std::size_t, std::size_t>> where;
    std::uint64_t bytes = 0;  ///< every group's
    packing::LocalPose local;

    static std::vector<std::vector<std::size_t>> grouping(const std::vector<Clip>& clips) {
        std::vector<const Clip*> ptrs;
        for (const Clip& c : clips) ptrs.push_back(&c);
        std::vector<std::vector<std::size_t>> out;
        for (const auto& g : packing::group_clips(ptrs)) {
            std::vector<std::size_t> frames;
            for (std::size_t i : g) frames.push_back(clips[i].frame_count());
            for (auto& part : packing::split_by_frames(g, frames, packing::kMaxGroupFrames)) out.push_back(std::move(part));
        }
        return out;
    }

    /// Decoders of packed groups (one blob per group, as pack() makes them); false when they do not fit
    /// the clips (cached bytes of other clips or of an older packing version).
    bool load(const std::vector<Clip>& clips, const Blobs& blobs) {
        const auto members = grouping(clips);
        if (blobs.size() != members.size()) return false;
        where.assign(clips.size(), {});
        groups.clear();
        bytes = 0;
        try {
            for (std::size_t g = 0; g < members.size(); ++g) {
                bytes += blobs[g].size();
                groups.emplace_back(blobs[g]);
                if (groups.back().clip_count() != members[g].size()) return false;
                for (std::size_t m = 0; m < members[g].size(); ++m) {
                    if (groups.back().frame_count(m) != clips[members[g][m]].frame_count()) return false;
                    where[members[g][m]] = {g, m};
                }
            }
        } catch (const Error&) {
            return false;  // an older packing version
        }
        return true;
    }

    /// Every group packed at E by pack_measured (bytes that meet E, as `mocapdb pack` stores them).
    static Blobs pack(const std::vector<Clip>& clips, double E, int threads) {
        Blobs out;
        for (const auto& m : grouping(clips)) {
            std::vector<const Clip*> ptrs;
            for (std::size_t i : m) ptrs.push_back(&clips[i]);
            packing::PackOptions options;
            options.max_error_cm = E;
            options.threads = threads;
            out.push_back(std::move(packing::pack_measured(ptrs, options).packed.bytes));
        }
        return out;
    }
};

// ---- measuring ----

struct Sample {
    std::size_t clip, frame;
};

/// `count` poses drawn uniformly over every frame of the clips.
std::vector<Sample> random_poses(const std::vector<Clip>& clips, std::size_t count, std::uint64_t seed) {
    std::vector<std::uint64_t> ends;
    std::uint64_t sum = 0;
    for (const Clip& c : clips) ends.push_back(sum += c.frame_count());
    std::mt19937_64 rng(seed);
    std::vector<Sample> out;
    for (std::size_t p = 0; p < count; ++p) {
        const std::uint64_t u = rng() % sum;
        const auto k = static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), u) - ends.begin());
        out.push_back({k, static_cast<std::size_t>(u - (k == 0 ? 0 : ends[k - 1]))});
    }
    return out;
}

struct Measured {
    packing::ErrorStats error;
    std::vector<double> cpu_us, wall_us;
};

/// Max / p99 (resolution 20 E / 8192) / RMSE of the codec's local poses against the source, every joint and frame of every clip.
packing::ErrorStats codec_error(PoseCodec& codec, const std::vector<Clip>& clips, const std::vector<MatX>& source, double E) {
    packing::ErrorAccumulator errors(20.0 * E);  // ACL reaches several times its precision
    packing::LocalPose local;
    GlobalPose global;
    for (std::size_t k = 0; k < clips.size(); ++k) {
        const Skeleton& skeleton = *clips[k].skeleton;
        MatX decoded(source[k].rows(), source[k].cols());
        for (std::size_t f = 0; f < clips[k].frame_count(); ++f) {
            codec.local_pose(k, f, local);
            forward_kinematics(skeleton, local.rotations, local.translations, global);
            for (std::size_t j = 0; j < skeleton.size(); ++j)
                decoded.block<3, 1>(3 * static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(f)) = global.positions[j];
        }
        packing::add_position_errors(source[k], decoded, errors);
    }
    return errors.stats();
}

/// The codecs timed, ACL first. A new decoder of ours: build it from the same clips at E (or from the
/// packed groups) beside `ours`, and push one more PoseCodec whose decode writes every joint's local
/// transform of (clip, frame) into its own buffer; the timing loop, the error and the table take it as is.
std::vector<PoseCodec> make_codecs(const std::shared_ptr<AclClips>& acl, const std::shared_ptr<PackedClips>& ours, bool index) {
    std::vector<PoseCodec> codecs;
    for (const bool bound : {false, true})
        codecs.push_back({bound ? "acl_ctx" : "acl", acl->bytes(),
                          [acl, bound](std::size_t k, std::size_t f) { return bound ? acl->decode_bound(k, f) : acl->decode(k, f); },
                          [acl, bound](std::size_t k, std::size_t f, packing::LocalPose& out) { acl->local_pose(k, f, bound, out); }});
    const auto ours_local = [ours](std::size_t k, std::size_t f, packing::LocalPose& out) {
        const auto [g, m] = ours->where[k];
        ours->groups[g].decode_local_pose(m, f, out);
    };
    codecs.push_back({"packed", ours->bytes,
                      [ours, ours_local](std::size_t k, std::size_t f) {
                          ours_local(k, f, ours->local);
                          return ours->local.rotations[1].w() + ours->local.translations[0].x();
                      },
                      ours_local});
    if (index) {  // a PoseIndex per group: bytes = the packed bytes it refers to + the index's memory
        auto indexes = std::make_shared<std::vector<std::unique_ptr<packing::PoseIndex>>>();
        std::uint64_t bytes = ours->bytes;
        for (const packing::GroupDecoder& g : ours->groups) {
            indexes->push_back(std::make_unique<packing::PoseIndex>(g));
            bytes += indexes->back()->memory_bytes();
        }
        const auto index_local = [ours, indexes](std::size_t k, std::size_t f, packing::LocalPose& out) {
            const auto [g, m] = ours->where[k];
            (*indexes)[g]->local_pose(m, f, out);
        };
        codecs.push_back({"index", bytes,
                          [ours, index_local](std::size_t k, std::size_t f) {
                              index_local(k, f, ours->local);
                              return ours->local.rotations[1].w() + ours->local.translations[0].x();
                          },
                          index_local});
    }
    return codecs;
}

/// Times every codec on the same sequence: per repeat, each codec in turn runs all of it once.
void time_codecs(std::vector<PoseCodec>& codecs, const std::vector<Sample>& poses, int repeats, std::vector<Measured>& out) {
    const std::size_t warm = std::min<std::size_t>(poses.size(), 2000);
    for (PoseCodec& c : codecs)
        for (std::size_t p = 0; p < warm; ++p) g_sink = g_sink + c.decode(poses[p].clip, poses[p].frame);
    const double n = static_cast<double>(poses.size());
    for (int r = 0; r < repeats; ++r)
        for (std::size_t i = 0; i < codecs.size(); ++i) {
            const auto& decode = codecs[i].decode;
            double sink = 0.0;
            const double cpu = thread_cpu_seconds();
            const double wall = wall_seconds();
            for (const Sample& s : poses) sink += decode(s.clip, s.frame);
            const double wall_s = wall_seconds() - wall;
            const double cpu_s = thread_cpu_seconds() - cpu;
            g_sink = g_sink + sink;
            out[i].cpu_us.push_back(cpu_s / n * 1e6);
            out[i].wall_us.push_back(wall_s / n * 1e6);
        }
}

/// One (folder, E): the table (unless json_only) and its JSON. Bytes ratio to codecs[0] (ACL), time ratio
/// to the faster ACL variant (thread CPU, min of repeats); compare.py's
/// figure from `reference` (ACL's table over the same clips) for the other codecs.
nlohmann::json report(const std::string& folder, double E, std::size_t clips, std::size_t frames,
                      const std::vector<PoseCodec>& codecs, const std::vector<Measured>& measured,
                      const eval::AclCollection& reference, bool json_only) {
    const bool usable = reference.complete() && !reference.settings.empty();
    const eval::AclSetting* csv = nullptr;
    for (const auto& s : reference.settings)
        if (usable && std::abs(s.precision_cm - E) < 1e-9) csv = &s;
    nlohmann::json row = {{"folder", folder}, {"E_cm", E}, {"clips", clips}, {"frames", frames}, {"codecs", nlohmann::json::array()}};
    if (csv != nullptr) row["acl_csv"] = {{"bytes", csv->bytes}, {"max_cm", csv->max_cm}, {"rmse_cm", csv->rmse_cm}};
    if (!json_only) {
        std::printf("\nE = %g cm\n", E);
        if (csv != nullptr)
            std::printf("  ACL's table (compare.py): %llu bytes, max %.4f cm; this run's ACL bytes are %+.2f %% of it\n",
                        static_cast<unsigned long long>(csv->bytes), csv->max_cm,
                        100.0 * (static_cast<double>(codecs[0].bytes) / static_cast<double>(csv->bytes) - 1.0));
        std::printf("  %-8s %10s %8s %8s %8s | %7s %7s %7s %7s | %9s %11s %9s\n", "codec", "bytes", "max cm", "p99 cm",
                    "rmse cm", "cpu min", "cpu med", "wallmin", "wallmed", "ACL/bytes", "x ACL @max", "us/ACL");
    }
    double acl_cpu = 1e300;  // the faster ACL variant's
    for (std::size_t i = 0; i < codecs.size(); ++i)
        if (codecs[i].name.rfind("acl", 0) == 0) acl_cpu = std::min(acl_cpu, best(measured[i].cpu_us));
    for (std::size_t i = 0; i < codecs.size(); ++i) {
        const Measured& m = measured[i];
        const double bytes_ratio = static_cast<double>(codecs[0].bytes) / static_cast<double>(codecs[i].bytes);
        const double time_ratio = best(m.cpu_us) / acl_cpu;
        std::optional<double> smaller;
        if (usable && codecs[i].name.rfind("acl", 0) != 0)
            smaller = eval::compare_with_acl(reference, static_cast<double>(codecs[i].bytes), m.error.max_cm, m.error.rmse_cm)
                          .smaller_at_max;
        if (!json_only) {
            char at_max[32] = "-";
            if (smaller) std::snprintf(at_max, sizeof at_max, "%.2fx", *smaller);
            std::printf("  %-8s %10llu %8.5f %8.5f %8.5f | %7.3f %7.3f %7.3f %7.3f | %8.2fx %11s %8.2fx\n",
                        codecs[i].name.c_str(), static_cast<unsigned long long>(codecs[i].bytes), m.error.max_cm,
                        m.error.p99_cm, m.error.rmse_cm, best(m.cpu_us), median(m.cpu_us), best(m.wall_us), median(m.wall_us),
                        bytes_ratio, at_max, time_ratio);
        }
        row["codecs"].push_back({{"name", codecs[i].name},
                                 {"bytes", codecs[i].bytes},
                                 {"max_cm", m.error.max_cm},
                                 {"p99_cm", m.error.p99_cm},
                                 {"rmse_cm", m.error.rmse_cm},
                                 {"pose_us_cpu_min", best(m.cpu_us)},
                                 {"pose_us_cpu_median", median(m.cpu_us)},
                                 {"pose_us_wall_min", best(m.wall_us)},
                                 {"pose_us_wall_median", median(m.wall_us)},
                                 {"acl_bytes_over_bytes", bytes_ratio},
                                 {"smaller_than_acl_at_max", smaller ? nlohmann::json(*smaller) : nlohmann::json()},
                                 {"pose_us_over_acl", time_ratio}});
    }
    return row;
}

}  // namespace

int main(int argc, char** argv) {
    std::string folder = "all", cache;
    std::vector<double> errors{1.0, 0.5, 0.1};
    std::size_t poses = 20000, limit = 0;
    int repeats = 5, threads = 2;
    std::uint64_t seed = 7;
    bool json = false, index = false;
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            auto next = [&]() -> std::string {
                if (i + 1 >= argc) throw InvalidArgument(a + " needs a value");
                return argv[++i];
            };
            if (a == "--folder") folder = next();
            else if (a == "--errors") errors = parse_doubles(next());
            else if (a == "--poses") poses = std::stoul(next());
            else if (a == "--repeats") repeats = std::max(1, std::stoi(next()));
            else if (a == "--seed") seed = std::stoull(next());
            else if (a == "--limit") limit = std::stoul(next());
            else if (a == "--threads") threads = std::max(1, std::stoi(next()));
            else if (a == "--cache") cache = next();
            else if (a == "--json") json = true;
            else if (a == "--index") index = true;
            else throw InvalidArgument("unknown argument " + a);
        }
        if (poses == 0) throw InvalidArgument("--poses must be positive");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_acl_runtime: %s\n", e.what());
        return 2;
    }
    const std::vector<std::string> folders =
        folder == "all" ? std::vector<std::string>{"cmu-walkrun-pfnn", "cmu-asfamc"} : std::vector<std::string>{folder};
    nlohmann::json doc = {{"poses", poses}, {"repeats", repeats}, {"seed", seed}, {"results", nlohmann::json::array()}};
    try {
        for (const std::string& name : folders) {
            const std::vector<Clip> clips = read_shared_folder(name, limit);
            std::vector<std::string> stems;
            std::vector<MatX> source;
            std::size_t frames = 0;
            for (const Clip& c : clips) {
                stems.push_back(c.name);
                source.push_back(joint_positions(c));
                frames += c.frame_count();
            }
            const fs::path table = fs::path(MOCAPDB_SHARED_DIR) / "reference" / "acl" / (name + ".csv");
            eval::AclCollection reference;
            if (fs::exists(table)) reference = eval::aggregate_acl(eval::read_acl_table(table), stems);
            const std::vector<Sample> sequence = random_poses(clips, poses, seed);
            if (!json)
                std::printf("\n%s: %zu clips, %zu frames, %zu joints with end sites; %zu random poses, %d repeats, one thread\n",
                            name.c_str(), clips.size(), frames, clips.front().skeleton->size(), poses, repeats);
            for (double E : errors) {
                auto acl = std::make_shared<AclClips>();
                auto ours = std::make_shared<PackedClips>();
                Blobs blobs;
                double acl_s = 0.0, pack_s = 0.0;
                if (cache.empty() || !read_blobs(cache_file(cache, name, clips.size(), E, "acl"), blobs) || !acl->adopt(blobs)) {
                    acl = std::make_shared<AclClips>();
                    const double t = wall_seconds();
                    acl->compress(clips, E);
                    acl_s = wall_seconds() - t;
                    if (!cache.empty()) write_blobs(cache_file(cache, name, clips.size(), E, "acl"), acl->blobs());
                }
                blobs.clear();
                if (cache.empty() || !read_blobs(cache_file(cache, name, clips.size(), E, "packed"), blobs) ||
                    !ours->load(clips, blobs)) {
                    const double t = wall_seconds();
                    blobs = PackedClips::pack(clips, E, threads);
                    pack_s = wall_seconds() - t;
                    if (!ours->load(clips, blobs)) throw Error("packed groups do not match the clips");
                    if (!cache.empty()) write_blobs(cache_file(cache, name, clips.size(), E, "packed"), blobs);
                }

                std::vector<PoseCodec> codecs = make_codecs(acl, ours, index);
                std::vector<Measured> measured(codecs.size());
                for (std::size_t i = 0; i < codecs.size(); ++i) measured[i].error = codec_error(codecs[i], clips, source, E);
                time_codecs(codecs, sequence, repeats, measured);

                nlohmann::json row = report(name, E, clips.size(), frames, codecs, measured, reference, json);
                row["acl_compress_s"] = acl_s > 0 ? nlohmann::json(acl_s) : nlohmann::json();  // null: from --cache
                row["pack_s"] = pack_s > 0 ? nlohmann::json(pack_s) : nlohmann::json();
                if (!json && acl_s + pack_s > 0) std::printf("  ACL compress %.1f s wall, pack %.1f s wall\n", acl_s, pack_s);
                doc["results"].push_back(row);
                std::fflush(stdout);
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_acl_runtime: %s\n", e.what());
        return 1;
    }
    if (json) std::printf("%s\n", doc.dump(2).c_str());
    return 0;
}
