#include "mocapdb/io/text_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include "mocapdb/core/error.hpp"

namespace mocapdb {

std::string read_text_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(path.string() + ": cannot open for reading: " + std::strerror(errno));
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) throw IoError(path.string() + ": read failed");
    return std::move(buffer).str();
}

void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
    std::random_device rd;
    const std::filesystem::path tmp =
        path.string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(rd() & 0xffffff);
    try {
        {
            std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
            if (!out) throw IoError(path.string() + ": cannot create " + tmp.string() + ": " + std::strerror(errno));
            write(out);
            out.flush();
            if (!out) throw IoError(path.string() + ": write failed: " + std::strerror(errno));
        }
        // Make the data durable before the rename publishes it.
        const int fd = ::open(tmp.c_str(), O_RDONLY);
        if (fd >= 0) {
            ::fsync(fd);
            ::close(fd);
        }
        std::error_code ec;
        std::filesystem::rename(tmp, path, ec);
        if (ec) throw IoError(path.string() + ": cannot replace: " + ec.message());
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        throw;
    }
}

}  // namespace mocapdb
