#include "mocapdb/core/float32.hpp"
#include "mocapdb/compression/codecs/deflate.hpp"

#include <cmath>
#include <cstring>
#include <limits>

#include <zlib.h>

#include "byte_stream.hpp"

namespace mocapdb::compression::codecs {
namespace detail {
std::uint32_t crc32_of(const std::uint8_t* data, std::size_t size, std::uint32_t seed) {
    uLong crc = seed;
    while (size > 0) {
        const uInt chunk = static_cast<uInt>(std::min<std::size_t>(size, 1u << 30));
        crc = ::crc32(crc, data, chunk);
        data += chunk;
        size -= chunk;
    }
    return static_cast<std::uint32_t>(crc);
}
}  // namespace detail

namespace {
constexpr char kDeflateMagic[4] = {'M', 'C', 'D', 'F'};
constexpr std::uint8_t kDeflateVersion = 1;
constexpr const char* kDeflateSource = "float32-deflate stream";
constexpr std::size_t kMaxZlibInput = std::numeric_limits<uInt>::max();
}  // namespace

Bytes deflate_bytes(const std::uint8_t* data, std::size_t size, int level) {
    if (level < -1 || level > 9)
        throw InvalidArgument("deflate_bytes: level must be -1 or 0..9, got " + std::to_string(level));
    if (size > kMaxZlibInput)
        throw InvalidArgument("deflate_bytes: buffer of " + std::to_string(size) + " bytes exceeds zlib's 4 GiB limit");
    static const std::uint8_t empty = 0;
    if (data == nullptr) data = &empty;
    Bytes out(compressBound(static_cast<uLong>(size)));
    uLongf out_size = static_cast<uLongf>(out.size());
    const int rc = compress2(out.data(), &out_size, data, static_cast<uLong>(size), level);
    if (rc != Z_OK) throw InvalidArgument("deflate_bytes: zlib compress2 failed (" + std::to_string(rc) + ")");
    out.resize(out_size);
    return out;
}

Bytes deflate_bytes(const Bytes& data, int level) { return deflate_bytes(data.data(), data.size(), level); }

Bytes inflate_bytes(const std::uint8_t* data, std::size_t size, std::size_t expected_size, const std::string& source) {
    auto fail = [&](const std::string& message) -> void { throw ParseError(source, 0, 0, message); };
    if (size > kMaxZlibInput || expected_size > kMaxZlibInput) fail("zlib stream or its output exceeds 4 GiB");
    // Deflate cannot expand more than about 1032:1: refuse before allocating a forged output size.
    if (expected_size / 1032 > size + 64)
        fail(std::to_string(size) + " bytes of deflate data cannot decode to the expected " +
             std::to_string(expected_size) + " bytes (truncated stream or wrong dimensions)");
    Bytes out(expected_size + 1);  // one spare byte detects streams that decode to more
    z_stream zs;
    std::memset(&zs, 0, sizeof zs);
    if (inflateInit(&zs) != Z_OK) fail("zlib inflateInit failed");
    static std::uint8_t empty = 0;
    zs.next_in = const_cast<Bytef*>(size > 0 ? data : &empty);
    zs.avail_in = static_cast<uInt>(size);
    zs.next_out = out.data();
    zs.avail_out = static_cast<uInt>(out.size());
    const int rc = inflate(&zs, Z_FINISH);
    const std::size_t produced = out.size() - zs.avail_out;
    const std::size_t unread = zs.avail_in;
    const std::string zmsg = zs.msg != nullptr ? std::string(" (") + zs.msg + ")" : std::string();
    inflateEnd(&zs);
    if (rc == Z_DATA_ERROR) fail("corrupt deflate data" + zmsg);
    if (rc != Z_STREAM_END) {
        if (produced > expected_size)
            fail("deflate data decodes to more than the expected " + std::to_string(expected_size) + " bytes");
        fail("truncated deflate data: decoded " + std::to_string(produced) + " of " + std::to_string(expected_size) +
             " bytes" + zmsg);
    }
    if (produced != expected_size)
        fail("deflate data decodes to " + std::to_string(produced) + " bytes, expected " +
             std::to_string(expected_size));
    if (unread != 0) fail(std::to_string(unread) + " unexpected bytes after the end of the deflate data");
    out.resize(expected_size);
    return out;
}

Tensor3 round_to_float32(const Tensor3& a) {
    Tensor3 out(a.dimension(0), a.dimension(1), a.dimension(2));
    for (Eigen::Index i = 0; i < a.size(); ++i) out.data()[i] = float32_value(a.data()[i]);
    return out;
}

EncodedStream encode_float32_deflate(const Tensor3& a, const Float32DeflateOptions& options) {
    if (a.size() == 0) throw InvalidArgument("encode_float32_deflate: empty tensor");
    const std::size_t n = static_cast<std::size_t>(a.size());
    Bytes image(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const double v = a.data()[i];
        const float f = static_cast<float>(v);
        if (!std::isfinite(v) || !std::isfinite(f))
            throw InvalidArgument("encode_float32_deflate: element " + std::to_string(i) + " (" + std::to_string(v) +
                                  ") is not finite in float32");
        std::uint32_t bits;
        std::memcpy(&bits, &f, 4);
        for (std::size_t b = 0; b < 4; ++b) {
            const std::uint8_t byte = static_cast<std::uint8_t>(bits >> (8 * b));
            if (options.shuffle) image[b * n + i] = byte;
            else image[4 * i + b] = byte;
        }
    }
    const Bytes payload = deflate_bytes(image, options.level);
    detail::ByteWriter h;
    h.bytes(reinterpret_cast<const std::uint8_t*>(kDeflateMagic), 4);
    h.u8(kDeflateVersion);
    h.u8(options.shuffle ? 1 : 0);
    for (int k = 0; k < 3; ++k) h.u32(static_cast<std::uint32_t>(a.dimension(k)));
    return detail::finish_stream(h, payload);
}

Tensor3 decode_float32_deflate(const std::uint8_t* data, std::size_t size) {
    detail::ByteReader r(data, size, kDeflateSource);
    r.expect_magic(kDeflateMagic, kDeflateVersion);
    const std::uint8_t shuffle = r.u8("shuffle flag");
    if (shuffle > 1) r.fail("shuffle flag must be 0 or 1, found " + std::to_string(shuffle));
    std::uint64_t dims[3];
    const std::uint64_t n = detail::read_dimensions(r, dims, kMaxZlibInput / 4);
    const std::size_t payload = r.expect_payload();
    const Bytes image = inflate_bytes(r.here(), payload, static_cast<std::size_t>(4 * n), kDeflateSource);
    Tensor3 out(static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]),
                static_cast<Eigen::Index>(dims[2]));
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t bits = 0;
        for (std::size_t b = 0; b < 4; ++b)
            bits |= static_cast<std::uint32_t>(shuffle ? image[b * n + i] : image[4 * i + b]) << (8 * b);
        float f;
        std::memcpy(&f, &bits, 4);
        if (!std::isfinite(f)) r.fail_at(r.position(), "decoded value " + std::to_string(i) + " is not finite");
        out.data()[i] = static_cast<double>(f);
    }
    return out;
}

Tensor3 decode_float32_deflate(const Bytes& stream) { return decode_float32_deflate(stream.data(), stream.size()); }

}  // namespace mocapdb::compression::codecs
