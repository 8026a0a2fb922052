#include "mocapdb/store/store_error.hpp"

namespace mocapdb {
namespace {

std::string compose(const std::string& file, const std::string& path, const std::string& message) {
    std::string out = file;
    if (!path.empty()) out += (out.empty() ? "" : ": ") + path;
    return out.empty() ? message : out + ": " + message;
}

}  // namespace

StoreError::StoreError(std::string file, std::string object_path, const std::string& message)
    : Error(compose(file, object_path, message)),
      file_(std::move(file)),
      object_path_(std::move(object_path)),
      message_(message) {}

}  // namespace mocapdb
