#pragma once
// Little-endian writer/reader of the packed group's header fields (internal to the packing module).
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "../core/byte_stream.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::packing::detail {

class ByteWriter {
public:
    explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}
    template <class T>
    void raw(T value) {
        std::uint8_t b[sizeof(T)];
        std::memcpy(b, &value, sizeof(T));
        out_.insert(out_.end(), b, b + sizeof(T));
    }
    void u8(std::uint8_t v) { out_.push_back(v); }
    void f32(double v) { raw(static_cast<float>(v)); }
    void varint(std::uint64_t v) { byte_stream::put_varint(out_, v); }
    void text(const std::string& s) {
        varint(s.size());
        out_.insert(out_.end(), s.begin(), s.end());
    }
    void bytes(const std::vector<std::uint8_t>& b) { out_.insert(out_.end(), b.begin(), b.end()); }

private:
    std::vector<std::uint8_t>& out_;
};

class ByteReader {
public:
    ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    template <class T>
    T raw() {
        need(sizeof(T));
        T v;
        std::memcpy(&v, data_ + pos_, sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    std::uint8_t u8() { return raw<std::uint8_t>(); }
    double f32() { return static_cast<double>(raw<float>()); }
    std::uint64_t varint() {
        if (const auto v = byte_stream::read_varint([this] { return u8(); })) return *v;
        throw Error("packed group: malformed varint at byte " + std::to_string(pos_));
    }
    std::string text() {
        const auto n = varint();
        need(n);
        std::string s(reinterpret_cast<const char*>(data_ + pos_), n);
        pos_ += n;
        return s;
    }
    std::size_t position() const { return pos_; }
    std::size_t size() const { return size_; }

private:
    void need(std::size_t n) const {
        if (n > size_ - pos_)
            throw Error("packed group: truncated (needs " + std::to_string(n) + " bytes at " + std::to_string(pos_) +
                        " of " + std::to_string(size_) + ")");
    }
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
};

}  // namespace mocapdb::packing::detail
