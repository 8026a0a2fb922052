#pragma once
// One writing session per database at a time: an exclusive flock(2) on "TARGET.lock" beside the
// target, held from before the session reads the target until the session ends. The kernel releases
// the lock when its holder exits, kill -9 included. Readers take no lock: they see the last published
// file. The lock file stays, except that a session which created nothing (its target does not exist)
// removes it while still holding it (remove_file); a lock is only taken as held when the name still
// names the locked inode, so two sessions never hold locks on different files.
#include <filesystem>

namespace mocapdb::store {

class WriterLock {
public:
    /// Waits up to `wait_seconds` (0: not at all) for the lock. StoreError naming the target when
    /// another session still holds it then; IoError when the lock file cannot be opened.
    WriterLock(const std::filesystem::path& target, double wait_seconds);
    ~WriterLock();
    WriterLock(const WriterLock&) = delete;
    WriterLock& operator=(const WriterLock&) = delete;

    /// "TARGET.lock".
    static std::filesystem::path lock_path(const std::filesystem::path& target);
    /// Removes the lock file and releases the lock (for a session that leaves no database behind).
    void remove_file() noexcept;

private:
    std::filesystem::path path_;
    int fd_ = -1;
};

}  // namespace mocapdb::store
