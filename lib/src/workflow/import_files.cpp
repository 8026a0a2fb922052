// Importing clip files into a database session, one file at a time.
#include "mocapdb/workflow/import_files.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/io/asf_amc.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/motion/figure_height.hpp"
#include "mocapdb/store/sha256.hpp"

namespace mocapdb::workflow {

std::vector<std::filesystem::path> collect_clip_files(const std::vector<std::filesystem::path>& inputs) {
    namespace fs = std::filesystem;
    std::vector<fs::path> out;
    std::set<fs::path> seen;
    auto add = [&](const fs::path& p) {
        std::error_code ec;
        fs::path key = fs::weakly_canonical(p, ec);
        if (ec) key = p;
        if (seen.insert(key).second) out.push_back(p);
    };
    for (const fs::path& input : inputs) {
        std::error_code ec;
        if (!fs::exists(input, ec)) throw IoError(input.string() + ": no such file or folder");
        if (!fs::is_directory(input, ec)) {
            add(input);
            continue;
        }
        std::vector<fs::path> found;
        for (fs::recursive_directory_iterator it(input, fs::directory_options::skip_permission_denied, ec), end;
             !ec && it != end; it.increment(ec)) {
            if (it->is_regular_file(ec) && clip_format_of(it->path())) found.push_back(it->path());
        }
        if (ec) throw IoError(input.string() + ": cannot list the folder: " + ec.message());
        std::sort(found.begin(), found.end());
        for (const fs::path& p : found) add(p);
    }
    return out;
}

namespace {

// A file that cannot be read or holds nothing: reported and skipped whatever keep_going says.
class UnusableFile : public IoError {
public:
    using IoError::IoError;
};

// Reads and parses one file into `clip` and `source`. False when its SHA-256 is already stored
// (imported.result says so). Throws the reader's errors.
bool read_source(const std::filesystem::path& path, const ImportOptions& options, const DatabaseWriter& db,
                 std::map<std::filesystem::path, std::shared_ptr<const Skeleton>>& asf_cache, ImportSummary& summary,
                 std::uint64_t& done, std::uint64_t total, const ProgressCallback& progress, ImportedFile& imported,
                 Clip& clip, ClipSource& source) {
    namespace fs = std::filesystem;
    const std::string name = path.filename().string();
    if (progress) progress(Progress{done, total, name});
    const auto format = clip_format_of(path);
    if (!format)
        throw InvalidArgument(path.string() + ": unsupported file type '" + path.extension().string() +
                              "' (expected .bvh or .amc)");
    std::string text;
    try {
        text = read_text_file(path);
    } catch (const IoError& e) {
        throw UnusableFile(e.what());
    }
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
        throw UnusableFile(path.string() + ": the file is empty (" + std::to_string(text.size()) + " bytes)");
    imported.bytes = text.size();
    const std::string sha = sha256_hex(text);
    ++summary.files;
    summary.bytes_read += imported.bytes;
    done += imported.bytes;

    if (const auto existing = db.find_sha256(sha)) {
        imported.result = {*existing, false, "skipped: duplicate sha256 of clip " + *existing};
        return false;
    }

    const ManifestEntry* entry = options.manifest ? options.manifest->find(path) : nullptr;
    std::optional<double> rate = options.frame_rate;
    if (entry && entry->frame_rate) rate = entry->frame_rate;
    source.file_name = name;
    source.sha256 = sha;
    if (entry) {
        source.subject = entry->subject;
        source.description = entry->description;
        source.labels = entry->labels;
    }
    if (*format == ClipFormat::Bvh) {
        BvhReadOptions o;
        o.strict = options.strict;
        o.frame_rate = rate;
        o.position_channels = options.bvh_positions;
        clip = parse_bvh(text, path.string(), o, &imported.warnings);
        source.format = "bvh";
    } else {
        fs::path asf = options.asf;
        if (asf.empty()) {
            const auto found = find_asf_for_amc(path);
            if (!found)
                throw Refused<InvalidArgument>(Remedy::NameSkeletonFile,
                                               path.string() +
                                                   ": no skeleton given and none found beside it by the CMU naming "
                                                   "(NN_MM.amc -> NN.asf)");
            asf = *found;
        }
        auto& skeleton = asf_cache[asf];
        if (!skeleton) skeleton = read_asf(asf);
        AmcReadOptions o;
        o.strict = options.strict;
        if (rate) o.frame_rate = *rate;
        clip = parse_amc(text, path.string(), skeleton, o, &imported.warnings);
        source.format = "amc";
        source.skeleton_file = asf.filename().string();
    }
    text = std::string();  // release the source text before storing
    if (clip.frame_count() > 0) {
        const std::string tall = figure_height_warning(figure_height(*clip.skeleton, clip.frame(0)));
        if (!tall.empty()) imported.warnings.push_back(Warning{path.string(), 0, tall});
    }
    return true;
}

}  // namespace

ImportSummary import_files(DatabaseWriter& db, const std::vector<std::filesystem::path>& files,
                           const ImportOptions& options, const ProgressCallback& progress,
                           const std::function<void(const ImportedFile&)>& on_file) {
    namespace fs = std::filesystem;
    std::uint64_t total = 0;
    for (const fs::path& p : files) {
        std::error_code ec;
        const auto size = fs::file_size(p, ec);
        if (!ec) total += size;
    }
    std::map<fs::path, std::shared_ptr<const Skeleton>> asf_cache;  // skeletons are small; clips are not kept
    ImportSummary summary;
    std::uint64_t done = 0;
    for (const fs::path& path : files) {
        ImportedFile imported;
        imported.file = path;
        Clip clip;
        ClipSource source;
        // Reading and parsing: with keep_going a bad file is reported and the others go on. Nothing
        // of it has reached the database yet.
        try {
            if (!read_source(path, options, db, asf_cache, summary, done, total, progress, imported, clip, source)) {
                ++summary.skipped;
                if (on_file) on_file(imported);
                continue;
            }
        } catch (const UnusableFile& e) {
            imported.error = e.what();
            ++summary.failed;
            if (on_file) on_file(imported);
            continue;
        } catch (const Error& e) {
            if (!options.keep_going) throw;
            imported.error = e.what();
            ++summary.failed;
            if (on_file) on_file(imported);
            continue;
        }
        imported.frames = clip.frame_count();
        imported.seconds = clip.duration();
        imported.result = db.add_clip(clip, source);
        if (imported.result.added) {
            ++summary.added;
            summary.frames += imported.frames;
            summary.seconds += imported.seconds;
        } else {
            ++summary.skipped;
        }
        if (on_file) on_file(imported);
    }
    if (progress) progress(Progress{done, total, {}});
    return summary;
}

}  // namespace mocapdb::workflow
