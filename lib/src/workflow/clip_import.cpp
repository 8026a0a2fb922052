#include "mocapdb/workflow/clip_import.hpp"

#include <chrono>
#include <memory>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::workflow {

ImportOutcome import_clips(const std::filesystem::path& db, const std::vector<std::filesystem::path>& inputs,
                           const ImportOptions& options, bool force, const ProgressCallback& progress) {
    namespace fs = std::filesystem;
    const std::vector<fs::path> files = collect_clip_files(inputs);
    if (files.empty()) throw InvalidArgument("no .bvh or .amc files found in the given inputs");
    ImportOutcome o;
    std::error_code ec;
    o.existed = fs::exists(db, ec);
    const auto mode = force ? DatabaseWriter::Mode::Create : DatabaseWriter::Mode::OpenOrCreate;
    std::unique_ptr<DatabaseWriter> writer;
    try {
        writer = std::make_unique<DatabaseWriter>(db, mode);
    } catch (const StoreError& e) {
        throw Refused<StoreError>(Remedy::ReplaceFile, e.file(), e.object_path(),
                                  e.message() + " (import appends to a mocapdb database)");
    }
    const auto start = std::chrono::steady_clock::now();
    o.summary = import_files(*writer, files, options, progress, [&](const ImportedFile& f) {
        for (const Warning& w : f.warnings) o.messages.push_back({ImportMessage::Kind::Warning, w.to_string()});
        if (!f.error.empty()) {
            o.messages.push_back({ImportMessage::Kind::Error, f.error});
        } else if (!f.result.added) {
            o.not_added.push_back(f.file.string() + ": " + f.result.message);
        }
    });
    // Nothing added: nothing to publish (a new database is not created empty, an existing one is
    // left as it was, even with force).
    if (o.summary.added > 0) writer->commit();
    writer.reset();
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (std::filesystem::exists(db, ec)) {
        const Database view(db);
        o.clips_in_db = view.clip_count();
        o.file_bytes = view.file_size();
    }
    return o;
}

}  // namespace mocapdb::workflow
