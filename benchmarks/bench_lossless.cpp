// The lossless tier (format v3 channels_packed) on the shared CMU folders: for each folder, the
// database `mocapdb import` writes (file bytes, import time) against the clips as float32 channels
// and against gzip -9 of the source text; then the alternatives behind the defaults of
// packing::pack_channels (zstd level, predictor order, decimal detection), packing every clip of the folder
// again and summing the zstd bytes and CPU time. Prints one "folder name value unit" line per figure.
// Usage: bench_lossless [SHARED_DIR]   (default: ../shared beside the repository)
#include "bench_timing.hpp"
#include <sys/resource.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "mocapdb/packing/lossless_channels.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/import_files.hpp"

using namespace mocapdb;
using namespace mocapdb::bench;
namespace fs = std::filesystem;

namespace {

double cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    auto sec = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
    return sec(usage.ru_utime) + sec(usage.ru_stime);
}

// Sum over the folder's clip files (extension `ext`) of `gzip -9 -c FILE | wc -c`.
std::uint64_t gzip9_bytes(const fs::path& folder, const std::string& ext) {
    const std::string cmd = "for f in '" + folder.string() + "'/*." + ext +
                            "; do gzip -9 -c \"$f\" | wc -c; done | awk '{s += $1} END {print s}'";
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
    unsigned long long total = 0;
    if (!pipe || std::fscanf(pipe.get(), "%llu", &total) != 1) return 0;
    return total;
}

std::uint64_t text_bytes(const fs::path& folder, const std::string& ext) {
    std::uint64_t total = 0;
    for (const auto& e : fs::directory_iterator(folder))
        if (e.path().extension() == "." + ext) total += e.file_size();
    return total;
}

void run_folder(const fs::path& folder, const std::string& ext, std::optional<double> fps, const fs::path& tmp) {
    const std::string name = folder.filename().string();
    const fs::path db_path = tmp / (name + ".h5");
    fs::remove(db_path);
    const auto start = Clock::now();
    const double cpu0 = cpu_seconds();
    {
        DatabaseWriter writer(db_path, DatabaseWriter::Mode::Create);
        workflow::ImportOptions options;
        options.frame_rate = fps;
        workflow::import_files(writer, workflow::collect_clip_files({folder}), options);
        writer.commit();
    }
    const double wall = seconds_since(start);
    const double cpu = cpu_seconds() - cpu0;

    const Database db(db_path);
    std::vector<Clip> clips;
    std::uint64_t float32 = 0, stored = 0, frames = 0;
    for (const ClipRecord& r : db.clips()) {
        clips.push_back(db.load_clip(r.id));
        float32 += 4ull * r.frames * r.channels;
        stored += r.stored_bytes;
        frames += r.frames;
    }
    const std::uint64_t file = fs::file_size(db_path);
    const std::uint64_t gzip = gzip9_bytes(folder, ext);
    std::printf("%s clips %zu\n%s frames %llu\n", name.c_str(), clips.size(), name.c_str(),
                static_cast<unsigned long long>(frames));
    std::printf("%s source_text %llu bytes\n%s gzip9_source_text %llu bytes\n", name.c_str(),
                static_cast<unsigned long long>(text_bytes(folder, ext)), name.c_str(), static_cast<unsigned long long>(gzip));
    std::printf("%s float32_channels %llu bytes\n%s database_file %llu bytes\n%s packed_channels_stored %llu bytes\n",
                name.c_str(), static_cast<unsigned long long>(float32), name.c_str(),
                static_cast<unsigned long long>(file), name.c_str(), static_cast<unsigned long long>(stored));
    std::printf("%s ratio_float32_to_file %.3f\n%s ratio_gzip9_to_file %.3f\n", name.c_str(),
                static_cast<double>(float32) / static_cast<double>(file), name.c_str(),
                static_cast<double>(gzip) / static_cast<double>(file));
    std::printf("%s import_wall %.2f s\n%s import_cpu %.2f s\n", name.c_str(), wall, name.c_str(), cpu);

    struct Variant {
        const char* label;
        packing::LosslessOptions options;
    };
    std::vector<Variant> variants;
    for (const int level : {3, 9, 15, 19, 22}) {
        packing::LosslessOptions o;
        o.zstd_level = level;
        variants.push_back({level == 3 ? "best-order_zstd3" : level == 9 ? "best-order_zstd9" : level == 15 ? "best-order_zstd15"
                                                             : level == 19 ? "best-order_zstd19" : "best-order_zstd22", o});
    }
    for (const int order : {1, 2}) {
        packing::LosslessOptions o;
        o.predictor = order;
        variants.push_back({order == 1 ? "order1_zstd19" : "order2_zstd19", o});
    }
    {
        packing::LosslessOptions o;
        o.detect_decimals = false;
        variants.push_back({"float64-bits-xor_zstd19", o});
    }
    for (const Variant& v : variants) {
        std::uint64_t bytes = 0, raw_channels = 0, channels = 0;
        std::array<std::uint64_t, 4> sections{};
        const double c0 = cpu_seconds();
        for (const Clip& clip : clips) {
            const packing::PackedChannels p = packing::pack_channels(clip.channels, packing::reader_scales(*clip.skeleton), v.options);
            bytes += p.bytes.size();
            for (std::size_t i = 0; i < sections.size(); ++i) sections[i] += p.section_bytes[i];
            for (const std::int64_t d : p.decimals) raw_channels += d == packing::kRawChannel;
            channels += p.channels();
        }
        std::printf("%s %s %llu bytes %.2f s_cpu_encode_and_verify %llu/%llu raw_channels sections_before_zstd %llu %llu "
                    "%llu %llu\n",
                    name.c_str(), v.label, static_cast<unsigned long long>(bytes), cpu_seconds() - c0,
                    static_cast<unsigned long long>(raw_channels), static_cast<unsigned long long>(channels),
                    static_cast<unsigned long long>(sections[0]), static_cast<unsigned long long>(sections[1]),
                    static_cast<unsigned long long>(sections[2]), static_cast<unsigned long long>(sections[3]));
    }
    // Decoding the default form of every clip (what Database::load_clip adds to the HDF5 read).
    std::vector<packing::PackedChannels> packed;
    for (const Clip& clip : clips) packed.push_back(packing::pack_channels(clip.channels, packing::reader_scales(*clip.skeleton)));
    const double decode = best_of(3, [&] {
        for (const packing::PackedChannels& p : packed) g_sink = g_sink + packing::unpack_channels(p)(0, 0);
    });
    std::printf("%s decode_all_clips %.3f s (%.1f M values/s)\n", name.c_str(), decode,
                1e-6 * static_cast<double>(float32 / 4) / decode);
}

}  // namespace

int main(int argc, char** argv) {
    const fs::path shared = argc > 1 ? fs::path(argv[1]) : fs::path(MOCAPDB_SHARED_DIR);
    const fs::path datasets = shared / "datasets";
    if (!fs::exists(datasets / "cmu-asfamc") || !fs::exists(datasets / "cmu-walkrun-pfnn")) {
        std::fprintf(stderr, "bench_lossless: %s has no cmu-asfamc / cmu-walkrun-pfnn\n", datasets.string().c_str());
        return 1;
    }
    const fs::path tmp = fs::temp_directory_path() / ("bench-lossless-" + std::to_string(getpid()));
    fs::create_directories(tmp);
    run_folder(datasets / "cmu-asfamc", "amc", std::nullopt, tmp);
    run_folder(datasets / "cmu-walkrun-pfnn", "bvh", 60.0, tmp);
    fs::remove_all(tmp);
    return 0;
}
