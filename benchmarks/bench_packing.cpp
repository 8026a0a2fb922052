// The packed collection codec (lib/include/mocapdb/packing/) on the shared CMU folders, beside ACL.
//
//   bench_packing [--folder cmu-asfamc|cmu-walkrun-pfnn|all] [--errors 1,0.5,0.1] [--window 32]
//                 [--rounding 0.5] [--threads 2] [--limit N] [--no-verify]
//
// Per folder and E: bytes (everything the decoder needs), ratio to float32 channels, bytes per second
// of motion, bits per joint per frame, max / p99 / RMSE cm (measured at encode time on every source
// frame, and again independently by decoding every clip: verify_max_cm), encode seconds, decode µs per
// pose (random access) and MB/s of float32 channels streaming (window by window), one line of
// key=value per (folder, E), plus the compare.py command to place it beside ACL.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "shared_folder.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/packed_group.hpp"

namespace fs = std::filesystem;
using namespace mocapdb;
using namespace mocapdb::bench;

namespace {

std::size_t probes_windows(const std::vector<packing::GroupDecoder>& decoders) {
    std::size_t n = 0;
    for (const auto& d : decoders)
        for (std::size_t k = 0; k < d.clip_count(); ++k) n += d.window_count(k);
    return n;
}

}  // namespace

int main(int argc, char** argv) {
    std::string folder = "all";
    std::vector<double> errors{1.0, 0.5, 0.1};
    packing::PackOptions options;
    options.format = packing::PackFormat::Archive;  // the archive codec's windows, bases and zstd comparison
    std::size_t limit = 0;
    bool verify = true;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--folder") folder = next();
        else if (a == "--errors") errors = parse_doubles(next());
        else if (a == "--window") options.window = std::stoi(next());
        else if (a == "--rounding") options.rounding = std::stod(next());
        else if (a == "--threads") options.threads = std::stoi(next());
        else if (a == "--limit") limit = std::stoul(next());
        else if (a == "--no-verify") verify = false;
        else if (a == "--zstd") options.compare_zstd = true;
        else if (a == "--rounding-search") options.rounding_search = true;
        else if (a == "--trim-tail") options.trim_tail = std::stoi(next());
        else if (a == "--time-basis") {
            const std::string v = next();
            options.time_basis = v == "learned" ? packing::TimeBasis::Learned
                                 : v == "cosine" ? packing::TimeBasis::Cosine : packing::TimeBasis::Auto;
        } else if (a == "--dof-basis") {
            const std::string v = next();
            options.dof_basis = v == "learned" ? packing::DofBasis::Learned
                                : v == "identity" ? packing::DofBasis::Identity : packing::DofBasis::Auto;
        }
        else {
            std::fprintf(stderr, "unknown argument %s\n", a.c_str());
            return 2;
        }
    }
    std::vector<std::string> folders;
    if (folder == "all") folders = {"cmu-walkrun-pfnn", "cmu-asfamc"};
    else folders = {folder};

    for (const auto& name : folders) {
        const auto t_read = Clock::now();
        const std::vector<Clip> clips = read_shared_folder(name, limit);
        const double read_s = seconds_since(t_read);
        std::vector<const Clip*> ptrs;
        for (const Clip& c : clips) ptrs.push_back(&c);
        const auto groups = packing::group_clips(ptrs);
        std::size_t frames = 0, f32_bytes = 0, positions_per_frame_sum = 0;
        double seconds = 0.0;
        for (const Clip& c : clips) {
            frames += c.frame_count();
            f32_bytes += c.frame_count() * c.skeleton->channel_count() * 4;
            seconds += static_cast<double>(c.frame_count()) / c.frame_rate;
            positions_per_frame_sum += c.frame_count() * c.skeleton->size();
        }
        std::printf("# %s: %zu clips, %zu frames, %zu groups, float32 channels %zu bytes, read %.1f s\n", name.c_str(),
                    clips.size(), frames, groups.size(), f32_bytes, read_s);
        for (double E : errors) {
            options.max_error_cm = E;
            std::size_t bytes = 0, header = 0, table = 0, payload = 0, probes = 0, zw = 0, zd = 0, zs = 0;
            std::string bases;
            std::size_t raw_windows = 0;
            double encode_s = 0.0, max_cm = 0.0, p99_cm = 0.0, sq = 0.0;
            std::size_t positions = 0;
            std::vector<packing::GroupDecoder> decoders;
            std::vector<std::vector<std::size_t>> members;
            const auto t_pack = Clock::now();
            for (const auto& g : groups) {
                std::vector<const Clip*> group;
                for (std::size_t i : g) group.push_back(ptrs[i]);
                packing::PackedGroup packed = packing::pack_group(group, options);
                const auto& s = packed.stats;
                bytes += s.bytes;
                header += s.header_bytes;
                table += s.table_bytes;
                payload += s.payload_bytes;
                probes += s.probes;
                bases += std::string(bases.empty() ? "" : ",") +
                         (s.time_basis == packing::TimeBasis::Cosine ? "cosine" : "learned") + "/" +
                         (s.dof_basis == packing::DofBasis::Identity ? "identity" : "learned");
                zw += s.zstd_window_bytes;
                raw_windows += s.raw_windows;
                zd += s.zstd_dictionary_bytes;
                zs += s.zstd_stream_bytes;
                max_cm = std::max(max_cm, s.error.max_cm);
                p99_cm = std::max(p99_cm, s.error.p99_cm);  // max over groups (upper bound of the pooled p99)
                sq += s.error.rmse_cm * s.error.rmse_cm * static_cast<double>(s.error.positions);
                positions += s.error.positions;
                decoders.emplace_back(std::move(packed.bytes));
                members.push_back(g);
            }
            encode_s = seconds_since(t_pack);
            const double rmse = std::sqrt(sq / static_cast<double>(std::max<std::size_t>(1, positions)));

            // Independent check: decode every clip, FK, compare with the source.
            double verify_max = 0.0;
            double stream_s = 0.0;
            if (verify) {
                for (std::size_t g = 0; g < decoders.size(); ++g)
                    for (std::size_t k = 0; k < members[g].size(); ++k) {
                        const Clip& src = *ptrs[members[g][k]];
                        const auto t = Clock::now();
                        const Clip dec = decoders[g].decode_clip(k);
                        stream_s += seconds_since(t);
                        const MatX a = joint_positions(src);
                        const MatX b = joint_positions(dec);
                        for (Eigen::Index f = 0; f < a.cols(); ++f)
                            for (Eigen::Index j = 0; j < a.rows(); j += 3)
                                verify_max = std::max(verify_max, (a.block<3, 1>(j, f) - b.block<3, 1>(j, f)).norm());
                    }
            }
            // Random access: single poses at random (clip, frame), one thread.
            std::mt19937 rng(7);
            const int poses = 20000;
            std::vector<double> row(512);
            const auto t_pose = Clock::now();
            for (int p = 0; p < poses; ++p) {
                const std::size_t g = rng() % decoders.size();
                const std::size_t k = rng() % decoders[g].clip_count();
                const std::size_t f = rng() % decoders[g].frame_count(k);
                row.resize(decoders[g].skeleton(k)->channel_count());
                decoders[g].decode_pose(k, f, row.data());
                g_sink = g_sink + row[0];
            }
            const double pose_us = seconds_since(t_pose) / poses * 1e6;
            const double joints_avg = static_cast<double>(positions_per_frame_sum) / static_cast<double>(frames);
            std::printf(
                "folder=%s E=%g window=%d rounding=%s clips=%zu frames=%zu bytes=%zu header_bytes=%zu table_bytes=%zu "
                "payload_bytes=%zu ratio_f32=%.2f bytes_per_s=%.1f bits_per_joint_frame=%.3f max_cm=%.5f p99_cm=%.5f "
                "rmse_cm=%.5f verify_max_cm=%.5f encode_s=%.2f decode_pose_us=%.2f "
                "stream_MB_s=%.1f\n",
                name.c_str(), E, options.window, options.rounding_search ? "search" : std::to_string(options.rounding).substr(0, 4).c_str(), clips.size(), frames, bytes, header, table, payload,
                static_cast<double>(f32_bytes) / static_cast<double>(bytes), static_cast<double>(bytes) / seconds,
                8.0 * static_cast<double>(bytes) / (static_cast<double>(frames) * joints_avg), max_cm, p99_cm, rmse,
                verify_max, encode_s, pose_us,
                verify && stream_s > 0 ? static_cast<double>(f32_bytes) / stream_s / 1e6 : 0.0);
            std::printf("#   compare: python3 compare.py %s.csv --bytes %zu --max-cm %.5f --rmse-cm %.5f\n", name.c_str(),
                        bytes, max_cm, rmse);
            if (options.compare_zstd)
                std::printf("#   payload alternatives: range coder %zu, zstd-19 per window %zu, per window + trained dictionary %zu, "
                            "one stream (no random access) %zu\n", payload, zw, zd, zs);
            std::printf("#   bases (time/dof) per group: %s; windows stored as source rows: %zu\n", bases.c_str(), raw_windows);
            std::printf("#   probes per window %.2f\n", static_cast<double>(probes) / static_cast<double>(std::max<std::size_t>(1, decoders.empty() ? 1 : probes_windows(decoders))));
            std::fflush(stdout);
        }
    }
    return 0;
}
