#include "mocapdb/core/float32.hpp"
#include "mocapdb/compression/codecs/zfp_codec.hpp"

#include <cmath>
#include <limits>
#include <memory>

#include <zfp.h>

#include "byte_stream.hpp"

namespace mocapdb::compression::codecs {
namespace {

constexpr char kZfpMagic[4] = {'M', 'C', 'Z', 'F'};
constexpr std::uint8_t kZfpVersion = 1;
constexpr const char* kZfpSource = "zfp stream";
constexpr std::uint8_t kZfpPerDof = 1;
constexpr std::uint64_t kZfpMaxElements = std::uint64_t{1} << 28;  // 2 GiB of doubles

struct ZfpHandles {
    zfp_field* field = nullptr;
    zfp_stream* zfp = nullptr;
    bitstream* bits = nullptr;
    ~ZfpHandles() {
        if (zfp != nullptr) zfp_stream_close(zfp);
        if (bits != nullptr) stream_close(bits);
        if (field != nullptr) zfp_field_free(field);
    }
};

/// Compresses data (D by T by N doubles, column-major) at the tolerance; returns the zfp bytes.
Bytes compress(double* data, Eigen::Index D, Eigen::Index T, Eigen::Index N, double tolerance) {
    ZfpHandles h;
    h.field = zfp_field_3d(data, zfp_type_double, static_cast<std::size_t>(D), static_cast<std::size_t>(T),
                           static_cast<std::size_t>(N));
    h.zfp = zfp_stream_open(nullptr);
    if (h.field == nullptr || h.zfp == nullptr) throw std::bad_alloc();
    zfp_stream_set_accuracy(h.zfp, tolerance);
    const std::size_t max_size = zfp_stream_maximum_size(h.zfp, h.field);
    std::vector<std::uint64_t> buffer((max_size + 7) / 8 + 1);
    h.bits = stream_open(buffer.data(), buffer.size() * 8);
    if (h.bits == nullptr) throw std::bad_alloc();
    zfp_stream_set_bit_stream(h.zfp, h.bits);
    zfp_stream_rewind(h.zfp);
    const std::size_t size = zfp_compress(h.zfp, h.field);
    if (size == 0) throw InvalidArgument("zfp_encode: zfp_compress failed");
    const auto* p = reinterpret_cast<const std::uint8_t*>(buffer.data());
    return Bytes(p, p + size);
}

void check_tensor(const Tensor3& a) {
    if (a.size() == 0) throw InvalidArgument("zfp_encode: empty tensor");
    for (Eigen::Index i = 0; i < a.size(); ++i)
        if (!std::isfinite(a.data()[i]))
            throw InvalidArgument("zfp_encode: element " + std::to_string(i) + " is not finite");
}

EncodedStream finish(const Tensor3& a, std::uint8_t flags, double tolerance, const Bytes& payload) {
    detail::ByteWriter h;
    h.bytes(reinterpret_cast<const std::uint8_t*>(kZfpMagic), 4);
    h.u8(kZfpVersion);
    h.u8(flags);
    for (int k = 0; k < 3; ++k) h.u32(static_cast<std::uint32_t>(a.dimension(k)));
    h.f64(tolerance);
    return detail::finish_stream(h, payload);
}

}  // namespace

EncodedStream zfp_encode(const Tensor3& a, double tolerance) {
    check_tensor(a);
    if (!std::isfinite(tolerance) || tolerance <= 0.0)
        throw InvalidArgument("zfp_encode: tolerance must be finite and > 0, got " + std::to_string(tolerance));
    Tensor3 copy = a;  // zfp takes a non-const pointer
    const Bytes z = compress(copy.data(), a.dimension(0), a.dimension(1), a.dimension(2), tolerance);
    return finish(a, 0, tolerance, z);
}

EncodedStream zfp_encode(const Tensor3& a, const Eigen::Ref<const VecX>& eps) {
    check_tensor(a);
    const Eigen::Index D = a.dimension(0);
    if (eps.size() != D)
        throw InvalidArgument("zfp_encode: " + std::to_string(eps.size()) + " tolerances for " + std::to_string(D) +
                              " dofs");
    std::vector<float> stored(static_cast<std::size_t>(D));
    detail::ByteWriter w;
    for (Eigen::Index d = 0; d < D; ++d) {
        if (!std::isfinite(eps[d]) || eps[d] < 1e-30 || eps[d] > 1e30)
            throw InvalidArgument("zfp_encode: tolerance of dof " + std::to_string(d) + " is " +
                                  std::to_string(eps[d]) + " (must be finite, in [1e-30, 1e30])");
        float f = to_float32(eps[d]);
        if (static_cast<double>(f) > eps[d]) f = std::nextafter(f, 0.0f);
        stored[d] = f;
        w.f32(f);
    }
    Tensor3 scaled = a;
    for (Eigen::Index i = 0; i < scaled.size(); ++i) scaled.data()[i] /= static_cast<double>(stored[i % D]);
    const Bytes z = compress(scaled.data(), D, a.dimension(1), a.dimension(2), 1.0);
    w.bytes(z);
    return finish(a, kZfpPerDof, 1.0, w.buffer());
}

Tensor3 zfp_decode(const std::uint8_t* data, std::size_t size) {
    detail::ByteReader r(data, size, kZfpSource);
    r.expect_magic(kZfpMagic, kZfpVersion);
    const std::uint8_t flags = r.u8("flags");
    if (flags > 1) r.fail("unknown flags " + std::to_string(flags));
    std::uint64_t dims[3];
    detail::read_dimensions(r, dims, kZfpMaxElements);
    const std::uint64_t blocks = ((dims[0] + 3) / 4) * ((dims[1] + 3) / 4) * ((dims[2] + 3) / 4);
    const std::size_t tol_at = r.position();
    const double tolerance = r.f64("tolerance");
    if (!std::isfinite(tolerance) || tolerance <= 0.0 || tolerance < 1e-300 || tolerance > 1e300)
        r.fail_at(tol_at, "tolerance must be finite and > 0");
    const std::size_t payload = r.expect_payload();
    // Every zfp block costs at least one bit: refuse dimensions the payload cannot hold before
    // allocating them.
    if (blocks > 8 * static_cast<std::uint64_t>(payload))
        r.fail(std::to_string(payload) + " payload bytes cannot hold the " + std::to_string(blocks) +
               " zfp blocks of the stated dimensions");
    const auto D = static_cast<Eigen::Index>(dims[0]), T = static_cast<Eigen::Index>(dims[1]),
               N = static_cast<Eigen::Index>(dims[2]);
    std::vector<double> scale;
    if (flags & kZfpPerDof) {
        scale.resize(static_cast<std::size_t>(D));
        for (auto& s : scale) {
            const std::size_t at = r.position();
            const float f = r.f32("dof tolerance");
            if (!std::isfinite(f) || f <= 0.0f) r.fail_at(at, "dof tolerance must be finite and > 0");
            s = static_cast<double>(f);
        }
    }
    Tensor3 out(D, T, N);
    ZfpHandles h;
    h.field = zfp_field_3d(out.data(), zfp_type_double, dims[0], dims[1], dims[2]);
    h.zfp = zfp_stream_open(nullptr);
    if (h.field == nullptr || h.zfp == nullptr) throw std::bad_alloc();
    zfp_stream_set_accuracy(h.zfp, tolerance);
    // zfp does not check its input: decode from a copy padded with zeros to the largest size any
    // stream of these parameters can have, so a short or corrupt payload cannot make it read past
    // the buffer. The payload may not be longer than that size either.
    const std::size_t max_size = zfp_stream_maximum_size(h.zfp, h.field);
    if (r.remaining() > max_size)
        r.fail("zfp payload of " + std::to_string(r.remaining()) + " bytes exceeds the maximum " +
               std::to_string(max_size) + " for these dimensions");
    std::vector<std::uint64_t> buffer((max_size + 7) / 8 + 2, 0);
    std::memcpy(buffer.data(), r.here(), r.remaining());
    h.bits = stream_open(buffer.data(), buffer.size() * 8);
    if (h.bits == nullptr) throw std::bad_alloc();
    zfp_stream_set_bit_stream(h.zfp, h.bits);
    zfp_stream_rewind(h.zfp);
    const std::size_t used = zfp_decompress(h.zfp, h.field);
    if (used == 0) r.fail("zfp_decompress failed");
    if (used > r.remaining())
        r.fail("truncated zfp payload: " + std::to_string(r.remaining()) + " bytes, decoding needed " +
               std::to_string(used));
    for (Eigen::Index i = 0; i < out.size(); ++i) {
        if (!scale.empty()) out.data()[i] *= scale[static_cast<std::size_t>(i % D)];
        if (!std::isfinite(out.data()[i]))
            r.fail("decoded value " + std::to_string(i) + " is not finite (corrupt zfp payload)");
    }
    return out;
}

Tensor3 zfp_decode(const Bytes& stream) { return zfp_decode(stream.data(), stream.size()); }

}  // namespace mocapdb::compression::codecs
