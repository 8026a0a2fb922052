#pragma once
// Private helpers of the codec module: little-endian writer and a bounds-checked reader whose
// errors are ParseErrors naming the stream and the byte offset.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "../../core/byte_stream.hpp"
#include "mocapdb/compression/codecs/encoded_stream.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::compression::codecs::detail {

/// CRC-32 (zlib's polynomial) of a byte range, continuing from `crc` (0 to start).
std::uint32_t crc32_of(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0);

class ByteWriter {
public:
    void u8(std::uint8_t v) { out_.push_back(v); }
    void u16(std::uint16_t v) { put(v, 2); }
    void u32(std::uint32_t v) { put(v, 4); }
    void u64(std::uint64_t v) { put(v, 8); }
    void f32(float v) {
        std::uint32_t bits;
        std::memcpy(&bits, &v, 4);
        u32(bits);
    }
    void f64(double v) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, 8);
        u64(bits);
    }
    void bytes(const std::uint8_t* data, std::size_t size) { out_.insert(out_.end(), data, data + size); }
    void bytes(const Bytes& b) { bytes(b.data(), b.size()); }
    std::size_t size() const { return out_.size(); }
    Bytes& buffer() { return out_; }

private:
    void put(std::uint64_t v, int n) { byte_stream::put_le(out_, v, n); }
    Bytes out_;
};

class ByteReader {
public:
    ByteReader(const std::uint8_t* data, std::size_t size, std::string source)
        : data_(data), size_(size), source_(std::move(source)) {}

    std::size_t position() const { return pos_; }
    std::size_t remaining() const { return size_ - pos_; }
    const std::uint8_t* here() const { return data_ + pos_; }

    [[noreturn]] void fail(const std::string& message) const { fail_at(pos_, message); }
    [[noreturn]] void fail_at(std::size_t offset, const std::string& message) const {
        throw ParseError(source_, 0, 0, "byte " + std::to_string(offset) + ": " + message);
    }
    void need(std::size_t n, const char* what) const {
        if (n > remaining())
            fail("truncated: " + std::string(what) + " needs " + std::to_string(n) + " bytes, " +
                 std::to_string(remaining()) + " left");
    }
    std::uint8_t u8(const char* what) {
        need(1, what);
        return data_[pos_++];
    }
    std::uint16_t u16(const char* what) { return static_cast<std::uint16_t>(get(2, what)); }
    std::uint32_t u32(const char* what) { return static_cast<std::uint32_t>(get(4, what)); }
    std::uint64_t u64(const char* what) { return get(8, what); }
    float f32(const char* what) {
        const std::uint32_t bits = u32(what);
        float v;
        std::memcpy(&v, &bits, 4);
        return v;
    }
    double f64(const char* what) {
        const std::uint64_t bits = u64(what);
        double v;
        std::memcpy(&v, &bits, 8);
        return v;
    }
    const std::uint8_t* take(std::size_t n, const char* what) {
        need(n, what);
        const std::uint8_t* p = data_ + pos_;
        pos_ += n;
        return p;
    }
    /// Checks the 4-byte magic and the version byte.
    void expect_magic(const char magic[4], std::uint8_t version) {
        need(5, "magic and version");
        if (std::memcmp(data_, magic, 4) != 0)
            fail_at(0, std::string("not a ") + source_ + " (magic '" + std::string(magic, 4) + "' expected)");
        pos_ = 4;
        const std::uint8_t v = u8("version");
        if (v != version)
            fail_at(
                4, "format version " + std::to_string(v) + " not supported (expected " + std::to_string(version) + ")");
    }
    /// Reads the payload size and CRC-32 that end a header, checks that exactly that many bytes
    /// follow and that the CRC of the header (up to the CRC field) and the payload matches.
    /// Returns the payload size.
    std::size_t expect_payload() {
        const std::uint64_t size = u64("payload size");
        const std::size_t crc_at = pos_;
        const std::uint32_t crc = u32("payload CRC-32");
        if (size != remaining())
            fail("payload size " + std::to_string(size) + " does not match the " + std::to_string(remaining()) +
                 " bytes that follow the header" + (size > remaining() ? " (truncated stream)" : ""));
        if (crc32_of(here(), remaining(), crc32_of(data_, crc_at)) != crc) fail("checksum mismatch (corrupted stream)");
        return static_cast<std::size_t>(size);
    }
    void expect_end() const {
        if (remaining() != 0) fail(std::to_string(remaining()) + " unexpected bytes after the payload");
    }

private:
    std::uint64_t get(int n, const char* what) {
        need(static_cast<std::size_t>(n), what);
        const std::uint64_t v = byte_stream::get_le(data_ + pos_, n);
        pos_ += static_cast<std::size_t>(n);
        return v;
    }
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
    std::string source_;
};

/// Product of dims (each >= 1), failing with "too large" when it exceeds limit.
inline std::uint64_t checked_count(const ByteReader& r, const std::uint64_t* dims, int count, std::uint64_t limit) {
    std::uint64_t n = 1;
    for (int i = 0; i < count; ++i) {
        if (dims[i] != 0 && n > limit / dims[i]) r.fail("dimensions too large");
        n *= dims[i];
    }
    if (n > limit) r.fail("dimensions too large");
    return n;
}

/// Three u32 dimensions (each > 0) into dims; their product, failing with "too large" past limit.
inline std::uint64_t read_dimensions(ByteReader& r, std::uint64_t (&dims)[3], std::uint64_t limit) {
    for (auto& d : dims) {
        d = r.u32("dimension");
        if (d == 0) r.fail("a dimension is 0");
    }
    return checked_count(r, dims, 3, limit);
}

/// Ends a header: appends the payload size and the CRC-32 of (header so far, payload), then the
/// payload; returns the stream with header_bytes set.
inline EncodedStream finish_stream(ByteWriter& header, const Bytes& payload) {
    header.u64(payload.size());
    const std::uint32_t crc = crc32_of(payload.data(), payload.size(), crc32_of(header.buffer().data(), header.size()));
    header.u32(crc);
    EncodedStream out;
    out.header_bytes = header.size();
    out.bytes = std::move(header.buffer());
    out.bytes.insert(out.bytes.end(), payload.begin(), payload.end());
    return out;
}

}  // namespace mocapdb::compression::codecs::detail
