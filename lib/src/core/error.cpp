#include "mocapdb/core/error.hpp"

namespace mocapdb {
namespace {
std::string located(const std::string& file, std::size_t line, std::size_t column, const std::string& message) {
    std::string out = file;
    if (line > 0) out += ":" + std::to_string(line);
    if (column > 0) out += ":" + std::to_string(column);
    return out + ": " + message;
}
}  // namespace

ParseError::ParseError(std::string file, std::size_t line, std::size_t column, const std::string& message)
    : Error(located(file, line, column, message)),
      file_(std::move(file)),
      line_(line),
      column_(column),
      message_(message) {}

}  // namespace mocapdb
