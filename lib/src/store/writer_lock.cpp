#include "writer_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>

#include "mocapdb/core/error.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store {

std::filesystem::path WriterLock::lock_path(const std::filesystem::path& target) {
    return std::filesystem::path(target.string() + ".lock");
}

WriterLock::WriterLock(const std::filesystem::path& target, double wait_seconds) {
    if (!(wait_seconds >= 0.0) || !std::isfinite(wait_seconds))
        throw InvalidArgument("database writer: the lock wait must be a finite number of seconds >= 0");
    path_ = lock_path(target);
    const std::filesystem::path& path = path_;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_seconds);
    for (;;) {
        if (fd_ < 0) {
            fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
            if (fd_ < 0) throw IoError(path.string() + ": cannot open the writer lock: " + std::strerror(errno));
        }
        if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) {
            // The holder before us may have removed the file (remove_file): then the lock is on an
            // inode nobody else will open, and the name is locked afresh.
            struct stat held {
            }, named{};
            if (::fstat(fd_, &held) == 0 && ::stat(path.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
                held.st_ino == named.st_ino)
                return;
            ::close(fd_);
            fd_ = -1;
            continue;
        }
        const int err = errno;
        if (err != EWOULDBLOCK && err != EINTR) {
            ::close(fd_);
            throw IoError(path.string() + ": cannot take the writer lock: " + std::strerror(err));
        }
        if (std::chrono::steady_clock::now() >= deadline) {
            ::close(fd_);
            char waited[32];
            std::snprintf(waited, sizeof waited, "%.0f", wait_seconds);
            throw StoreError(target.string(), "",
                             std::string("another mocapdb session is writing this database (waited ") + waited +
                                 " s for it); nothing was changed, try again when it has finished");
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
}

WriterLock::~WriterLock() {
    if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

void WriterLock::remove_file() noexcept {
    if (fd_ < 0) return;
    ::unlink(path_.c_str());  // while still held: a waiter then finds the name gone and locks afresh
    ::close(fd_);
    fd_ = -1;
}

}  // namespace mocapdb::store
