#pragma once
// SHA-256 (FIPS 180-4), used to recognise a source file that was imported before.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace mocapdb {

/// Incremental SHA-256: update() any number of times, then hex_digest() once.
class Sha256 {
public:
    Sha256();
    void update(std::string_view bytes);
    /// The digest as 64 lowercase hex characters. The object must not be updated afterwards.
    std::string hex_digest();

private:
    void compress(const unsigned char* block);
    std::array<std::uint32_t, 8> state_;
    std::array<unsigned char, 64> buffer_{};
    std::size_t buffered_ = 0;
    std::uint64_t length_ = 0;  // bytes
};

/// SHA-256 of `bytes` as 64 lowercase hex characters.
std::string sha256_hex(std::string_view bytes);

}  // namespace mocapdb
