#include "segments.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <random>

#include "layout.hpp"
#include "root.hpp"
#include "temp_files.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::store {
namespace {

const char* const kReadersLock = "readers.lock";

std::filesystem::path folder_of(const std::filesystem::path& index) {
    return index.has_parent_path() ? index.parent_path() : std::filesystem::path(".");
}

}  // namespace

std::filesystem::path segment_dir(const std::filesystem::path& index) {
    return std::filesystem::path(index.string() + ".d");
}

std::string new_segment_name(const std::filesystem::path& index) {
    // One generator per thread: writers in several threads of one process draw names concurrently.
    thread_local std::mt19937_64 gen{std::random_device{}()};
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", &utc);
    for (;;) {
        char name[96];
        std::snprintf(name, sizeof name, "%s-%ld-%08x.h5", stamp, static_cast<long>(::getpid()),
                      static_cast<unsigned>(gen() & 0xffffffffu));
        const std::string link = segment_dir(index.filename()).string() + "/" + name;
        std::error_code ec;
        if (!std::filesystem::exists(segment_file(index, link), ec)) return link;
    }
}

std::filesystem::path segment_file(const std::filesystem::path& index, const std::string& link_name) {
    return folder_of(index) / link_name;
}

std::vector<std::string> top_level_objects(const h5::File& index) {
    std::vector<std::string> out;
    for (const std::string& top : {kSkeletons, kClips, kSets})
        for (const std::string& name : index.children(top)) out.push_back(top + "/" + name);
    if (index.external_target(kPacked) || index.exists(kPacked)) out.push_back(kPacked);
    return out;
}

std::set<std::string> referenced_segments(const h5::File& index) {
    std::set<std::string> out;
    for (const std::string& path : top_level_objects(index))
        if (const auto target = index.external_target(path)) out.insert(target->first);
    return out;
}

std::uint64_t stored_bytes_under(const h5::File& file, const std::string& path) {
    switch (file.type_of(path)) {
        case h5::ObjectType::Dataset: return file.dataset_info(path).stored_bytes;
        case h5::ObjectType::Group: {
            std::uint64_t bytes = 0;
            for (const std::string& name : file.children(path)) bytes += stored_bytes_under(file, path + "/" + name);
            return bytes;
        }
        default: return 0;
    }
}

std::size_t remove_unreferenced_segments(const std::filesystem::path& index, const std::set<std::string>& referenced) {
    const std::filesystem::path dir = segment_dir(index);
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) return 0;
    const int fd = ::open((dir / kReadersLock).c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return 0;
    std::size_t removed = 0;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
        std::set<std::filesystem::path> keep;
        for (const std::string& link : referenced) keep.insert(segment_file(index, link).lexically_normal());
        for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
            const std::filesystem::path p = entry.path();
            if (p.filename() == kReadersLock || keep.count(p.lexically_normal()) > 0) continue;
            std::error_code rm;
            if (std::filesystem::remove(p, rm)) ++removed;
        }
    }
    ::close(fd);  // releases the lock
    return removed;
}

void rewrite_live_objects(const std::filesystem::path& file) {
    const std::filesystem::path compact = make_temp_path(file);
    try {
        h5::File from = h5::File::open(file, false);
        h5::File to = h5::File::create(compact);
        const bool segment = from.read_string_attribute("/", "kind") == "segment";
        if (segment) {
            write_segment_root(to);
            for (const std::string& path : top_level_objects(from)) from.copy_to(to, path);
        } else {
            write_root_attributes(to);
            for (const std::string& top : {kSkeletons, kClips, kSets}) from.copy_to(to, top);
            if (const auto t = from.external_target(kPacked)) to.link_external(kPacked, t->first, t->second);
            else if (from.exists(kPacked)) from.copy_to(to, kPacked);
        }
        to.close();
        from.close();
    } catch (...) {
        std::error_code ec;
        std::filesystem::remove(compact, ec);
        throw;
    }
    std::error_code ec;
    std::filesystem::rename(compact, file, ec);
    if (ec) throw IoError(file.string() + ": cannot replace with " + compact.string() + ": " + ec.message());
}

void copy_database(const std::filesystem::path& from, const std::filesystem::path& to) {
    std::error_code ec;
    if (std::filesystem::exists(to, ec)) throw IoError(to.string() + ": exists (a database is copied to a new path)");
    std::set<std::string> referenced;
    {
        const h5::File index = h5::File::open(from, false);
        referenced = referenced_segments(index);
    }
    auto copy = [](const std::filesystem::path& a, const std::filesystem::path& b) {
        std::error_code e;
        std::filesystem::copy_file(a, b, std::filesystem::copy_options::none, e);
        if (e) throw IoError(a.string() + ": cannot copy to " + b.string() + ": " + e.message());
    };
    if (!referenced.empty()) {
        std::filesystem::create_directories(segment_dir(to), ec);
        if (ec) throw IoError(segment_dir(to).string() + ": cannot create the segment folder: " + ec.message());
        for (const std::string& link : referenced)
            copy(segment_file(from, link), segment_dir(to) / std::filesystem::path(link).filename());
    }
    copy(from, to);
    if (referenced.empty()) return;
    h5::File index = h5::File::open(to, true);
    const std::string folder = segment_dir(to.filename()).string();
    for (const std::string& path : top_level_objects(index))
        if (const auto t = index.external_target(path)) {
            index.unlink(path);
            index.link_external(path, folder + "/" + std::filesystem::path(t->first).filename().string(), t->second);
        }
    index.close();
}

std::uint64_t disk_bytes(const std::filesystem::path& index) {
    std::error_code ec;
    std::uint64_t bytes = std::filesystem::file_size(index, ec);
    if (ec) bytes = 0;
    for (const auto& entry : std::filesystem::directory_iterator(segment_dir(index), ec)) {
        std::error_code e;
        const auto n = std::filesystem::file_size(entry.path(), e);
        if (!e) bytes += n;
    }
    return bytes;
}

std::uint64_t referenced_bytes(const std::filesystem::path& index, const std::set<std::string>& referenced) {
    std::error_code ec;
    std::uint64_t bytes = std::filesystem::file_size(index, ec);
    if (ec) bytes = 0;
    for (const std::string& link : referenced) {
        std::error_code e;
        const auto n = std::filesystem::file_size(segment_file(index, link), e);
        if (!e) bytes += n;
    }
    return bytes;
}

ReaderLock::ReaderLock(const std::filesystem::path& index) {
    const std::filesystem::path dir = segment_dir(index);
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) return;
    const std::filesystem::path path = dir / kReadersLock;
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) return;
    // Blocks only while a writer removes unreferenced segments (milliseconds).
    while (::flock(fd_, LOCK_SH) != 0 && errno == EINTR) {}
}

ReaderLock::~ReaderLock() {
    if (fd_ >= 0) ::close(fd_);
}

}  // namespace mocapdb::store
