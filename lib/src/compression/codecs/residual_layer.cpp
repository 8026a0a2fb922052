#include "mocapdb/core/float32.hpp"
#include "mocapdb/compression/codecs/residual_layer.hpp"

#include <cmath>
#include <limits>

#include "byte_stream.hpp"
#include "mocapdb/compression/codecs/deflate.hpp"

namespace mocapdb::compression::codecs {
namespace {

constexpr char kResidualMagic[4] = {'M', 'C', 'R', 'L'};
constexpr std::uint8_t kResidualVersion = 1;
constexpr const char* kResidualSource = "residual stream";
constexpr std::uint8_t kResidualPerDof = 1, kResidualAllZero = 2;
constexpr double kResidualMaxCode = 2147483648.0;                       // 2^31
constexpr std::uint64_t kResidualMaxElements = std::uint64_t{1} << 28;  // 2 GiB of doubles

double step_of(float eps) { return 2.0 * static_cast<double>(eps) * (1.0 - std::ldexp(1.0, -20)); }

using byte_stream::put_varint;
using byte_stream::unzigzag;
using byte_stream::zigzag;

std::uint64_t get_varint(detail::ByteReader& r, const char* what) {
    if (const auto v = byte_stream::read_varint([&] { return r.u8(what); })) return *v;
    r.fail(std::string("varint too long in ") + what);
}

/// Storage index of the k-th code in the given order.
struct OrderMap {
    Eigen::Index D, T, N;
    ResidualOrder order;
    template <class F>
    void for_each(F f) const {
        if (order == ResidualOrder::Storage) {
            for (Eigen::Index i = 0; i < D * T * N; ++i) f(i, i % D);
        } else {
            for (Eigen::Index d = 0; d < D; ++d)
                for (Eigen::Index n = 0; n < N; ++n)
                    for (Eigen::Index t = 0; t < T; ++t) f(d + D * (t + T * n), d);
        }
    }
};

}  // namespace

ResidualEncoding encode_residual(const Tensor3& r, const Eigen::Ref<const VecX>& eps, const ResidualOptions& options) {
    const Eigen::Index D = r.dimension(0), T = r.dimension(1), N = r.dimension(2);
    if (r.size() == 0) throw InvalidArgument("encode_residual: empty residual tensor");
    if (eps.size() != D && eps.size() != 1)
        throw InvalidArgument("encode_residual: " + std::to_string(eps.size()) + " tolerances for " +
                              std::to_string(D) + " dofs (give D or 1)");
    if (options.deflate_level < -1 || options.deflate_level > 9)
        throw InvalidArgument("encode_residual: deflate level must be -1 or 0..9");
    if (options.order != ResidualOrder::DofMajor && options.order != ResidualOrder::Storage)
        throw InvalidArgument("encode_residual: unknown order");
    std::vector<float> stored(static_cast<std::size_t>(D));
    bool all_equal = true;
    for (Eigen::Index d = 0; d < D; ++d) {
        const double e = eps.size() == 1 ? eps[0] : eps[d];
        if (!std::isfinite(e) || e < static_cast<double>(std::numeric_limits<float>::min()) ||
            e > static_cast<double>(std::numeric_limits<float>::max()))
            throw InvalidArgument("encode_residual: tolerance of dof " + std::to_string(d) + " is " +
                                  std::to_string(e) + " (must be finite, in the normal float32 range, > 0)");
        float f = to_float32(e);
        if (static_cast<double>(f) > e) f = std::nextafter(f, 0.0f);
        stored[d] = f;
        if (f != stored[0]) all_equal = false;
    }
    for (Eigen::Index i = 0; i < r.size(); ++i)
        if (!std::isfinite(r.data()[i]))
            throw InvalidArgument("encode_residual: residual element " + std::to_string(i) + " is not finite");

    ResidualEncoding out;
    out.tolerance.resize(D);
    for (Eigen::Index d = 0; d < D; ++d) out.tolerance[d] = static_cast<double>(stored[d]);
    out.decoded = Tensor3(D, T, N);
    out.decoded.setZero();
    std::vector<std::int64_t> codes(static_cast<std::size_t>(r.size()), 0);
    for (Eigen::Index i = 0; i < r.size(); ++i) {
        const Eigen::Index d = i % D;
        const double step = step_of(stored[d]);
        const double x = r.data()[i];
        const double qd = std::round(x / step);
        if (std::abs(qd) > kResidualMaxCode)
            throw InvalidArgument("encode_residual: residual " + std::to_string(x) + " at dof " + std::to_string(d) +
                                  " is more than 2^31 tolerances (" + std::to_string(stored[d]) + ")");
        auto q = static_cast<std::int64_t>(qd);
        const double e = static_cast<double>(stored[d]);
        // The decoder computes q * step: pick the neighbour that meets the bound if rounding missed.
        for (std::int64_t cand : {q, q - 1, q + 1})
            if (std::abs(x - static_cast<double>(cand) * step) <= e) {
                q = cand;
                break;
            }
        const double decoded = static_cast<double>(q) * step;
        const double err = std::abs(x - decoded);
        if (err > e) throw std::logic_error("encode_residual: quantization bound violated (bug)");
        codes[static_cast<std::size_t>(i)] = q;
        out.decoded.data()[i] = decoded;
        out.max_abs_error = std::max(out.max_abs_error, err);
        if (q != 0) ++out.nonzero;
        out.max_abs_code = std::max<std::int64_t>(out.max_abs_code, q < 0 ? -q : q);
    }

    const std::uint8_t flags =
        static_cast<std::uint8_t>((all_equal ? 0 : kResidualPerDof) | (out.nonzero == 0 ? kResidualAllZero : 0));
    Bytes payload;
    if (out.nonzero != 0) {
        detail::ByteWriter w;
        if (all_equal) w.f32(stored[0]);
        else
            for (float f : stored) w.f32(f);
        payload = std::move(w.buffer());
        Bytes varints;
        varints.reserve(static_cast<std::size_t>(r.size()));
        OrderMap{D, T, N, options.order}.for_each(
            [&](Eigen::Index i, Eigen::Index) { put_varint(varints, zigzag(codes[static_cast<std::size_t>(i)])); });
        put_varint(payload, varints.size());
        const Bytes z = deflate_bytes(varints, options.deflate_level);
        payload.insert(payload.end(), z.begin(), z.end());
    }
    detail::ByteWriter h;
    h.bytes(reinterpret_cast<const std::uint8_t*>(kResidualMagic), 4);
    h.u8(kResidualVersion);
    h.u8(flags);
    h.u8(static_cast<std::uint8_t>(options.order));
    for (Eigen::Index k : {D, T, N}) h.u32(static_cast<std::uint32_t>(k));
    out.stream = detail::finish_stream(h, payload);
    return out;
}

ResidualEncoding encode_residual(const Tensor3& r, double eps, const ResidualOptions& options) {
    VecX e(1);
    e[0] = eps;
    return encode_residual(r, e, options);
}

Tensor3 decode_residual(const std::uint8_t* data, std::size_t size) {
    detail::ByteReader r(data, size, kResidualSource);
    r.expect_magic(kResidualMagic, kResidualVersion);
    const std::uint8_t flags = r.u8("flags");
    if (flags > 3) r.fail("unknown flags " + std::to_string(flags));
    const std::uint8_t order = r.u8("order");
    if (order > 1) r.fail("order must be 0 or 1, found " + std::to_string(order));
    std::uint64_t dims[3];
    const std::uint64_t count = detail::read_dimensions(r, dims, kResidualMaxElements);
    const std::size_t payload = r.expect_payload();
    const auto D = static_cast<Eigen::Index>(dims[0]), T = static_cast<Eigen::Index>(dims[1]),
               N = static_cast<Eigen::Index>(dims[2]);
    if (flags & kResidualAllZero) {
        if (payload != 0) r.fail("an all-zero residual has no payload, found " + std::to_string(payload) + " bytes");
        Tensor3 zero(D, T, N);
        zero.setZero();
        return zero;
    }
    std::vector<double> steps(static_cast<std::size_t>(D));
    for (Eigen::Index d = 0; d < D; ++d) {
        if (d > 0 && !(flags & kResidualPerDof)) {
            steps[d] = steps[0];
            continue;
        }
        const std::size_t at = r.position();
        const float e = r.f32("tolerance");
        if (!std::isfinite(e) || e < std::numeric_limits<float>::min())
            r.fail_at(at, "tolerance must be a finite normal float32 > 0");
        steps[d] = step_of(e);
    }
    const std::uint64_t varint_size = get_varint(r, "code stream length");
    if (varint_size < count || varint_size > 10 * count)
        r.fail("code stream length " + std::to_string(varint_size) + " cannot hold " + std::to_string(count) +
               " codes");
    const Bytes varints =
        inflate_bytes(r.here(), r.remaining(), static_cast<std::size_t>(varint_size), kResidualSource);
    detail::ByteReader vr(varints.data(), varints.size(), kResidualSource + std::string(" (codes)"));
    Tensor3 out(D, T, N);
    OrderMap{D, T, N, static_cast<ResidualOrder>(order)}.for_each([&](Eigen::Index i, Eigen::Index d) {
        const std::int64_t q = unzigzag(get_varint(vr, "code"));
        if (std::abs(static_cast<double>(q)) > kResidualMaxCode) vr.fail("code " + std::to_string(q) + " exceeds 2^31");
        out.data()[i] = static_cast<double>(q) * steps[d];
    });
    vr.expect_end();
    return out;
}

Tensor3 decode_residual(const Bytes& stream) { return decode_residual(stream.data(), stream.size()); }

}  // namespace mocapdb::compression::codecs
