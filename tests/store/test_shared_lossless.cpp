// Acceptance of the lossless tier (issue 14, item 1) on the shared CMU folders (skipped when
// ../shared/datasets is absent). Each folder is imported on its own, as the README says (the AMC
// folder with its ASF files; the PFNN BVH folder with --fps 60), then for every clip:
//  - the decoded channels equal a fresh parse of the source file bit for bit;
//  - `mocapdb export` writes text whose every number is the source text's number (each exported
//    number parses to the same double as the source's number at the same place; compared as
//    numbers, so the BVH writer's "0" for a source "-0.0" counts as the same value);
// and the database file is smaller than the clips as float32 channels (4 bytes x frames x channels)
// and than gzip -9 of the source text (the clip files, each compressed on its own). The figures are
// printed with WARN (benchmarks/RESULTS.md, "Lossless tier").
#include <catch2/catch.hpp>

#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>

#include "mocapdb/io/asf_amc.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/store/database.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

// The numbers of a motion text, keyed by where they are: AMC "frame/bone" -> values of that line,
// BVH "row" -> values of a MOTION data row. Parsed with strtod, as the text says.
using TextNumbers = std::map<std::string, std::vector<double>>;

std::vector<double> numbers_of(std::istringstream& line) {
    std::vector<double> out;
    std::string token;
    while (line >> token) out.push_back(std::strtod(token.c_str(), nullptr));
    return out;
}

TextNumbers amc_numbers(const std::string& text) {
    TextNumbers out;
    std::istringstream in(text);
    std::string line, frame;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#' || line[0] == ':') continue;
        std::istringstream words(line);
        std::string first;
        if (!(words >> first)) continue;
        if (first.find_first_not_of("0123456789\r") == std::string::npos) {
            frame = first.substr(0, first.find('\r'));
            continue;
        }
        out[frame + "/" + first] = numbers_of(words);
    }
    return out;
}

TextNumbers bvh_numbers(const std::string& text) {
    TextNumbers out;
    const auto motion = text.find("Frame Time:");
    std::istringstream in(text.substr(motion == std::string::npos ? text.size() : motion));
    std::string line;
    std::getline(in, line);  // the Frame Time line
    std::size_t row = 0;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::vector<double> v = numbers_of(words);
        if (!v.empty()) out[std::to_string(row++)] = std::move(v);
    }
    return out;
}

// Every number of the source text is in the exported text, at the same place, as the same number.
std::size_t compare_numbers(const std::string& clip, const TextNumbers& source, const TextNumbers& exported) {
    INFO("clip " << clip);
    CHECK(exported.size() == source.size());
    std::size_t values = 0, mismatches = 0;
    std::string first_mismatch;
    for (const auto& [where, numbers] : source) {
        const auto it = exported.find(where);
        if (it == exported.end() || it->second.size() != numbers.size()) {
            ++mismatches;
            if (first_mismatch.empty()) first_mismatch = where + " (missing or another count)";
            continue;
        }
        for (std::size_t k = 0; k < numbers.size(); ++k, ++values)
            if (!(numbers[k] == it->second[k])) {
                ++mismatches;
                if (first_mismatch.empty()) first_mismatch = where + " value " + std::to_string(k);
            }
    }
    INFO("first mismatch at " << first_mismatch);
    CHECK(mismatches == 0);
    return values;
}

std::uint64_t gzip9_bytes(const std::filesystem::path& folder, const std::string& ext) {
    const CommandResult r = run_command("for f in " + quoted(folder.string()) + "/*." + ext +
                                        "; do gzip -9 -c \"$f\" | wc -c; done | awk '{s += $1} END {print s}'");
    REQUIRE(r.exit_code == 0);
    return std::strtoull(r.out.c_str(), nullptr, 10);
}

struct Folder {
    std::string name;
    std::string ext;
    std::string import_options;
};

}  // namespace

TEST_CASE("lossless tier: both shared folders export every source number exactly, in fewer bytes than "
          "float32 and gzip -9",
          "[store][shared][acceptance][lossless]") {
    MOCAPDB_REQUIRE_CLI();
    for (const Folder& folder : {Folder{"cmu-asfamc", "amc", ""}, Folder{"cmu-walkrun-pfnn", "bvh", " --fps 60"}}) {
        MOCAPDB_REQUIRE_SHARED(datasets_dir() / folder.name);
        INFO("folder " << folder.name);
        TempDir tmp("lossless");
        const auto dir = folder_for_this_build(datasets_dir() / folder.name, "." + folder.ext, tmp.path());
        const auto db_path = tmp / (folder.name + ".h5");
        const CommandResult import =
            run_cli("import " + quoted(dir.string()) + folder.import_options + " -o " + quoted(db_path.string()));
        INFO(import.output);
        REQUIRE(import.exit_code == 0);
        const CommandResult valid = run_cli("validate " + quoted(db_path.string()));
        INFO(valid.output);
        CHECK(valid.exit_code == 0);

        const Database db(db_path);
        std::uint64_t float32 = 0, values = 0;
        std::map<std::string, std::shared_ptr<const Skeleton>> asf;
        const auto records = db.clips();
        REQUIRE(!records.empty());
        for (const ClipRecord& r : records) {
            INFO("clip " << r.id);
            float32 += 4ull * r.frames * r.channels;
            const Clip stored = db.load_clip(r.id);
            Clip source;
            if (folder.ext == "amc") {
                auto& skeleton = asf[r.source.skeleton_file];
                if (!skeleton) skeleton = read_asf(dir / r.source.skeleton_file);
                source = read_amc(dir / r.source.file_name, skeleton);
            } else {
                BvhReadOptions o;
                o.frame_rate = 60.0;
                source = read_bvh(dir / r.source.file_name, o);
            }
            CHECK(same_bits(stored.channels, source.channels));

            const auto out = tmp / (r.id + "." + folder.ext);
            const CommandResult e = run_cli("export " + quoted(db_path.string()) + " --clip " + quoted(r.id) + " -o " +
                                            quoted(out.string()));
            INFO(e.output);
            REQUIRE(e.exit_code == 0);
            const std::string source_text = file_bytes(dir / r.source.file_name);
            const std::string exported_text = file_bytes(out);
            values += folder.ext == "amc" ? compare_numbers(r.id, amc_numbers(source_text), amc_numbers(exported_text))
                                          : compare_numbers(r.id, bvh_numbers(source_text), bvh_numbers(exported_text));
        }
        CHECK(values == float32 / 4);  // every channel value was compared

        const std::uint64_t file = database_disk_bytes(db_path);
        const std::uint64_t gzip = gzip9_bytes(dir, folder.ext);
        REQUIRE(gzip > 0);
        WARN(folder.name << ": " << records.size() << " clips, " << values << " values; database file " << file
                         << " bytes; float32 channels " << float32 << " bytes (ratio "
                         << static_cast<double>(float32) / static_cast<double>(file) << ":1); gzip -9 of the source text "
                         << gzip << " bytes (ratio " << static_cast<double>(gzip) / static_cast<double>(file) << ":1)");
        CHECK(file < float32);
        CHECK(file < gzip);
    }
}
