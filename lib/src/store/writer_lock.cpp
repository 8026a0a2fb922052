#include "writer_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
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
    const std::filesystem::path path = lock_path(target);
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw IoError(path.string() + ": cannot open the writer lock: " + std::strerror(errno));
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_seconds);
    for (;;) {
        if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
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

}  // namespace mocapdb::store
