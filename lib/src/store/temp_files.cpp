#include "temp_files.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb::store {
namespace {

const std::string kMarker = ".tmp-mocapdb-";

void fsync_path(const std::filesystem::path& path, bool directory) {
    const int fd = ::open(path.c_str(), directory ? (O_RDONLY | O_DIRECTORY) : O_RDONLY);
    if (fd < 0) throw IoError(path.string() + ": cannot open to sync: " + std::strerror(errno));
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    // Some file systems refuse fsync on folders; the rename itself is still atomic there.
    if (rc != 0 && !(directory && (err == EINVAL || err == EBADF)))
        throw IoError(path.string() + ": fsync failed: " + std::strerror(err));
}

}  // namespace

std::filesystem::path make_temp_path(const std::filesystem::path& target) {
    std::random_device rd;
    std::mt19937 gen(rd());
    for (;;) {
        char hex[9];
        std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(gen()));
        std::filesystem::path p = target;
        p += kMarker + std::to_string(::getpid()) + "-" + hex;
        std::error_code ec;
        if (!std::filesystem::exists(p, ec)) return p;
    }
}

std::size_t remove_stale_temps(const std::filesystem::path& target) {
    const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
    const std::string prefix = target.filename().string() + kMarker;
    std::size_t removed = 0;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string rest = name.substr(prefix.size());
        const std::size_t dash = rest.find('-');
        if (dash == std::string::npos || dash == 0) continue;
        long pid = 0;
        try {
            pid = std::stol(rest.substr(0, dash));
        } catch (...) {
            continue;
        }
        if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
        // ESRCH: no such process, so nobody is writing this file any more.
        if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
        std::error_code rm;
        if (std::filesystem::remove(entry.path(), rm)) ++removed;
    }
    return removed;
}

void make_durable(const std::filesystem::path& file) {
    fsync_path(file, false);
    fsync_path(file.has_parent_path() ? file.parent_path() : std::filesystem::path("."), true);
}

void publish(const std::filesystem::path& temp, const std::filesystem::path& target) {
    fsync_path(temp, false);
    std::error_code ec;
    std::filesystem::rename(temp, target, ec);
    if (ec) throw IoError(target.string() + ": cannot replace with " + temp.string() + ": " + ec.message());
    const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
    fsync_path(dir, true);
}

}  // namespace mocapdb::store
