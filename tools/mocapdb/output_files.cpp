#include "output_files.hpp"

#include "mocapdb/core/error.hpp"

namespace mocapdb::cli {

void refuse_existing(const std::filesystem::path& path, bool force) {
    std::error_code ec;
    if (!force && !path.empty() && std::filesystem::exists(path, ec))
        throw IoError(path.string() + ": exists (pass --force to overwrite it)");
}

void refuse_existing(std::initializer_list<std::filesystem::path> paths, bool force) {
    for (const auto& p : paths) refuse_existing(p, force);
}

}  // namespace mocapdb::cli
