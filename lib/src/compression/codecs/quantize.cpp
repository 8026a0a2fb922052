#include "mocapdb/core/float32.hpp"
#include "mocapdb/compression/codecs/quantize.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "byte_stream.hpp"
#include "mocapdb/compression/codecs/deflate.hpp"

namespace mocapdb::compression::codecs {
namespace {

constexpr char kMatrixMagic[4] = {'M', 'C', 'Q', 'M'};
constexpr char kTuckerMagic[4] = {'M', 'C', 'Q', 'T'};
constexpr std::uint8_t kQuantizedVersion = 1;
constexpr const char* kMatrixSource = "quantized-matrix stream";
constexpr const char* kTuckerSource = "quantized-Tucker stream";
constexpr std::uint64_t kQuantizedMaxElements = std::uint64_t{1} << 28;  // 2 GiB of doubles

void check_bits(int bits, const char* where) {
    if (bits < 1 || bits > 16)
        throw InvalidArgument(std::string(where) + ": bits must be in 1..16, got " + std::to_string(bits));
}

void check_level(int level, const char* where) {
    if (level < -1 || level > 9)
        throw InvalidArgument(std::string(where) + ": deflate level must be -1 or 0..9, got " + std::to_string(level));
}

void check_consistent(const QuantizedColumns& q, const char* where) {
    const bool ok = q.bits >= 1 && q.bits <= 16 && q.rows >= 0 && q.cols >= 0 &&
                    q.offset.size() == static_cast<std::size_t>(q.cols) &&
                    q.step.size() == static_cast<std::size_t>(q.cols) &&
                    q.codes.size() == static_cast<std::size_t>(q.rows * q.cols);
    if (!ok) throw InvalidArgument(std::string(where) + ": inconsistent QuantizedColumns (bits, sizes)");
}

std::uint64_t packed_code_bytes(std::uint64_t count, int bits) {
    return (count * static_cast<std::uint64_t>(bits) + 7) / 8;
}
std::uint64_t plane_code_bytes(std::uint64_t count, int bits) { return count * (bits <= 8 ? 1u : 2u); }

/// Parameters then codes of one part, in the given layout, appended to out.
void write_part(const QuantizedColumns& q, Packing packing, Bytes& out) {
    detail::ByteWriter w;
    for (Eigen::Index c = 0; c < q.cols; ++c) {
        w.f32(q.offset[c]);
        w.f32(q.step[c]);
    }
    out.insert(out.end(), w.buffer().begin(), w.buffer().end());
    const std::size_t n = q.codes.size();
    if (packing == Packing::BitPacked) {
        const std::size_t start = out.size();
        out.resize(start + static_cast<std::size_t>(packed_code_bytes(n, q.bits)), 0);
        std::uint64_t bit = 0;
        for (std::size_t i = 0; i < n; ++i)
            for (int b = 0; b < q.bits; ++b, ++bit)
                if ((q.codes[i] >> b) & 1u) out[start + (bit >> 3)] |= static_cast<std::uint8_t>(1u << (bit & 7));
    } else {
        for (std::size_t i = 0; i < n; ++i) out.push_back(static_cast<std::uint8_t>(q.codes[i] & 0xffu));
        if (q.bits > 8)
            for (std::size_t i = 0; i < n; ++i) out.push_back(static_cast<std::uint8_t>(q.codes[i] >> 8));
    }
}

/// Reads one part of rows by cols at bits in the given layout.
QuantizedColumns read_part(detail::ByteReader& r, Eigen::Index rows, Eigen::Index cols, int bits, Packing packing) {
    QuantizedColumns q;
    q.bits = bits;
    q.rows = rows;
    q.cols = cols;
    q.offset.resize(static_cast<std::size_t>(cols));
    q.step.resize(static_cast<std::size_t>(cols));
    for (Eigen::Index c = 0; c < cols; ++c) {
        const std::size_t at = r.position();
        q.offset[c] = r.f32("column offset");
        q.step[c] = r.f32("column step");
        if (!std::isfinite(q.offset[c]) || !std::isfinite(q.step[c]) || q.step[c] < 0.0f)
            r.fail_at(at, "column " + std::to_string(c) + ": offset and step must be finite and step >= 0");
    }
    const std::size_t n = static_cast<std::size_t>(rows * cols);
    q.codes.resize(n);
    if (packing == Packing::BitPacked) {
        const std::uint8_t* p = r.take(static_cast<std::size_t>(packed_code_bytes(n, bits)), "packed codes");
        std::uint64_t bit = 0;
        for (std::size_t i = 0; i < n; ++i) {
            std::uint32_t v = 0;
            for (int b = 0; b < bits; ++b, ++bit) v |= static_cast<std::uint32_t>((p[bit >> 3] >> (bit & 7)) & 1u) << b;
            q.codes[i] = static_cast<std::uint16_t>(v);
        }
    } else {
        const std::uint8_t* lo = r.take(n, "code low bytes");
        const std::uint8_t* hi = bits > 8 ? r.take(n, "code high bytes") : nullptr;
        const std::uint32_t limit = (1u << bits) - 1u;
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t v = lo[i] | (hi != nullptr ? static_cast<std::uint32_t>(hi[i]) << 8 : 0u);
            if (v > limit) r.fail("code " + std::to_string(v) + " exceeds " + std::to_string(bits) + " bits");
            q.codes[i] = static_cast<std::uint16_t>(v);
        }
    }
    return q;
}

/// float32 nearest x from below (<= x).
float float_down(double x) {
    float f = to_float32(x);
    if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    return f;
}
/// float32 nearest x from above (>= x).
float float_up(double x) {
    float f = to_float32(x);
    if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
}

/// Core grouping: the core storage seen as a (group size) by (groups) matrix.
std::array<Eigen::Index, 2> core_groups(const tensor::Ranks& r, CoreGrouping g) {
    switch (g) {
        case CoreGrouping::FrontalSlice: return {r[0] * r[1], r[2]};
        case CoreGrouping::Mode0Fibre: return {r[0], r[1] * r[2]};
        case CoreGrouping::Whole: return {r[0] * r[1] * r[2], 1};
    }
    throw InvalidArgument("quantize_tucker: unknown core grouping");
}

}  // namespace

double QuantizedColumns::error_bound(Eigen::Index c) const {
    const double s = step.at(static_cast<std::size_t>(c));
    if (s > 0.0) return 0.5 * s;
    return std::ldexp(std::abs(static_cast<double>(offset.at(static_cast<std::size_t>(c)))), -24);
}

double QuantizedColumns::max_error_bound() const {
    double m = 0.0;
    for (Eigen::Index c = 0; c < cols; ++c) m = std::max(m, error_bound(c));
    return m;
}

QuantizedColumns quantize_columns(const Eigen::Ref<const MatX>& m, int bits) {
    check_bits(bits, "quantize_columns");
    if (!m.allFinite()) throw InvalidArgument("quantize_columns: the matrix has a non-finite element");
    QuantizedColumns q;
    q.bits = bits;
    q.rows = m.rows();
    q.cols = m.cols();
    q.offset.resize(static_cast<std::size_t>(q.cols));
    q.step.resize(static_cast<std::size_t>(q.cols));
    q.codes.resize(static_cast<std::size_t>(q.rows * q.cols));
    const double levels = std::ldexp(1.0, bits) - 1.0;
    for (Eigen::Index c = 0; c < q.cols; ++c) {
        if (q.rows == 0) {
            q.offset[c] = 0.0f;
            q.step[c] = 0.0f;
            continue;
        }
        const double lo = m.col(c).minCoeff(), hi = m.col(c).maxCoeff();
        if (std::abs(lo) > std::numeric_limits<float>::max() || std::abs(hi) > std::numeric_limits<float>::max())
            throw InvalidArgument("quantize_columns: column " + std::to_string(c) + " exceeds the float32 range");
        const float offset = float_down(lo);
        float step = hi > static_cast<double>(offset) ? float_up((hi - static_cast<double>(offset)) / levels) : 0.0f;
        q.offset[c] = offset;
        q.step[c] = step;
        for (Eigen::Index i = 0; i < q.rows; ++i) {
            double code = 0.0;
            if (step > 0.0f) code = std::round((m(i, c) - static_cast<double>(offset)) / static_cast<double>(step));
            code = std::min(std::max(code, 0.0), levels);
            q.codes[static_cast<std::size_t>(c * q.rows + i)] = static_cast<std::uint16_t>(code);
        }
    }
    return q;
}

MatX dequantize(const QuantizedColumns& q) {
    check_consistent(q, "dequantize");
    MatX m(q.rows, q.cols);
    for (Eigen::Index c = 0; c < q.cols; ++c)
        for (Eigen::Index i = 0; i < q.rows; ++i)
            m(i, c) =
                static_cast<double>(q.offset[c]) +
                static_cast<double>(q.codes[static_cast<std::size_t>(c * q.rows + i)]) * static_cast<double>(q.step[c]);
    return m;
}

EncodedStream encode_quantized(const QuantizedColumns& q, Packing packing, int deflate_level) {
    check_consistent(q, "encode_quantized");
    check_level(deflate_level, "encode_quantized");
    Bytes part;
    write_part(q, packing, part);
    detail::ByteWriter h;
    h.bytes(reinterpret_cast<const std::uint8_t*>(kMatrixMagic), 4);
    h.u8(kQuantizedVersion);
    h.u8(static_cast<std::uint8_t>(packing));
    h.u8(static_cast<std::uint8_t>(q.bits));
    h.u32(static_cast<std::uint32_t>(q.rows));
    h.u32(static_cast<std::uint32_t>(q.cols));
    return detail::finish_stream(h, packing == Packing::Deflated ? deflate_bytes(part, deflate_level) : part);
}

QuantizedColumns decode_quantized(const std::uint8_t* data, std::size_t size) {
    detail::ByteReader r(data, size, kMatrixSource);
    r.expect_magic(kMatrixMagic, kQuantizedVersion);
    const std::uint8_t packing = r.u8("packing");
    if (packing > 1) r.fail("packing must be 0 (bit-packed) or 1 (deflated), found " + std::to_string(packing));
    const int bits = r.u8("bits");
    if (bits < 1 || bits > 16) r.fail("bits must be in 1..16, found " + std::to_string(bits));
    std::uint64_t dims[2] = {r.u32("rows"), r.u32("cols")};
    const std::uint64_t n = detail::checked_count(r, dims, 2, kQuantizedMaxElements);
    if (dims[1] > kQuantizedMaxElements) r.fail("dimensions too large");
    const std::size_t payload = r.expect_payload();
    const auto pk = static_cast<Packing>(packing);
    const std::uint64_t part_size =
        8 * dims[1] + (pk == Packing::BitPacked ? packed_code_bytes(n, bits) : plane_code_bytes(n, bits));
    Bytes inflated;
    const std::uint8_t* part = r.here();
    if (pk == Packing::Deflated) {
        inflated = inflate_bytes(r.here(), payload, static_cast<std::size_t>(part_size), kMatrixSource);
        part = inflated.data();
    } else if (part_size != payload) {
        r.fail("payload of " + std::to_string(payload) + " bytes, expected " + std::to_string(part_size) + " for " +
               std::to_string(dims[0]) + " by " + std::to_string(dims[1]) + " codes of " + std::to_string(bits) +
               " bits");
    }
    detail::ByteReader pr(part, static_cast<std::size_t>(part_size), kMatrixSource);
    QuantizedColumns q =
        read_part(pr, static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]), bits, pk);
    pr.expect_end();
    return q;
}

std::size_t QuantizedTucker::best_bytes() const { return std::min(packed_bytes(), deflated_bytes()); }

QuantizedTucker quantize_tucker(const tensor::TuckerModel& model, const QuantizeTuckerOptions& options) {
    check_bits(options.core_bits, "quantize_tucker (core_bits)");
    check_bits(options.basis_bits, "quantize_tucker (basis_bits)");
    check_level(options.deflate_level, "quantize_tucker");
    const tensor::Ranks& r = model.ranks;
    const tensor::Dims3 dims = model.dims();
    tensor::check_ranks(dims, r, "quantize_tucker");
    if (model.core.dimension(0) != r[0] || model.core.dimension(1) != r[1] || model.core.dimension(2) != r[2])
        throw InvalidArgument("quantize_tucker: core shape does not match the ranks");
    for (int k = 0; k < 3; ++k)
        if (model.U[k].cols() != r[k])
            throw InvalidArgument("quantize_tucker: basis " + std::to_string(k) + " has " +
                                  std::to_string(model.U[k].cols()) + " columns, ranks say " + std::to_string(r[k]));
    const auto groups = core_groups(r, options.core_grouping);
    const Eigen::Map<const MatX> core_matrix(model.core.data(), groups[0], groups[1]);

    std::array<QuantizedColumns, 4> parts{
        quantize_columns(core_matrix, options.core_bits), quantize_columns(model.U[0], options.basis_bits),
        quantize_columns(model.U[1], options.basis_bits), quantize_columns(model.U[2], options.basis_bits)};

    QuantizedTucker out;
    tensor::TuckerModel& m = out.model;
    m.ranks = r;
    m.method = model.method;
    m.core = Tensor3(r[0], r[1], r[2]);
    Eigen::Map<MatX>(m.core.data(), groups[0], groups[1]) = dequantize(parts[0]);
    for (int k = 0; k < 3; ++k) m.U[k] = dequantize(parts[k + 1]);
    out.max_abs_error[0] =
        (Eigen::Map<const MatX>(m.core.data(), groups[0], groups[1]) - core_matrix).cwiseAbs().maxCoeff();
    for (int k = 0; k < 3; ++k) out.max_abs_error[k + 1] = (m.U[k] - model.U[k]).cwiseAbs().maxCoeff();
    for (int k = 0; k < 4; ++k) out.error_bound[k] = parts[k].max_error_bound();

    for (Packing packing : {Packing::BitPacked, Packing::Deflated}) {
        Bytes body;
        for (const auto& p : parts) write_part(p, packing, body);
        detail::ByteWriter h;
        h.bytes(reinterpret_cast<const std::uint8_t*>(kTuckerMagic), 4);
        h.u8(kQuantizedVersion);
        h.u8(static_cast<std::uint8_t>(packing));
        h.u8(static_cast<std::uint8_t>(options.core_bits));
        h.u8(static_cast<std::uint8_t>(options.basis_bits));
        h.u8(static_cast<std::uint8_t>(options.core_grouping));
        h.u8(static_cast<std::uint8_t>(model.method));
        for (int k = 0; k < 3; ++k) h.u32(static_cast<std::uint32_t>(dims[k]));
        for (int k = 0; k < 3; ++k) h.u32(static_cast<std::uint32_t>(r[k]));
        (packing == Packing::BitPacked ? out.packed : out.deflated) =
            detail::finish_stream(h, packing == Packing::Deflated ? deflate_bytes(body, options.deflate_level) : body);
    }
    return out;
}

tensor::TuckerModel decode_quantized_tucker(const std::uint8_t* data, std::size_t size) {
    detail::ByteReader r(data, size, kTuckerSource);
    r.expect_magic(kTuckerMagic, kQuantizedVersion);
    const std::uint8_t packing = r.u8("packing");
    if (packing > 1) r.fail("packing must be 0 (bit-packed) or 1 (deflated), found " + std::to_string(packing));
    const int core_bits = r.u8("core bits");
    const int basis_bits = r.u8("basis bits");
    if (core_bits < 1 || core_bits > 16 || basis_bits < 1 || basis_bits > 16) r.fail("bits must be in 1..16");
    const std::uint8_t grouping = r.u8("core grouping");
    if (grouping > 2) r.fail("core grouping must be 0, 1 or 2, found " + std::to_string(grouping));
    const std::uint8_t method = r.u8("method");
    if (method > 2) r.fail("method must be 0, 1 or 2, found " + std::to_string(method));
    std::uint64_t dims[3], ranks[3];
    for (auto& d : dims) d = r.u32("dimension");
    for (int k = 0; k < 3; ++k) {
        ranks[k] = r.u32("rank");
        if (dims[k] == 0 || ranks[k] == 0 || ranks[k] > dims[k])
            r.fail("rank " + std::to_string(ranks[k]) + " of mode " + std::to_string(k) + " must be in 1.." +
                   std::to_string(dims[k]));
    }
    const tensor::Ranks rk{static_cast<Eigen::Index>(ranks[0]), static_cast<Eigen::Index>(ranks[1]),
                           static_cast<Eigen::Index>(ranks[2])};
    const std::uint64_t core_count = detail::checked_count(r, ranks, 3, kQuantizedMaxElements);
    std::uint64_t basis_count[3];
    for (int k = 0; k < 3; ++k) {
        const std::uint64_t two[2] = {dims[k], ranks[k]};
        basis_count[k] = detail::checked_count(r, two, 2, kQuantizedMaxElements);
    }
    const auto pk = static_cast<Packing>(packing);
    const auto groups = core_groups(rk, static_cast<CoreGrouping>(grouping));
    auto part_size = [&](std::uint64_t count, std::uint64_t cols, int bits) {
        return 8 * cols + (pk == Packing::BitPacked ? packed_code_bytes(count, bits) : plane_code_bytes(count, bits));
    };
    std::uint64_t body_size = part_size(core_count, static_cast<std::uint64_t>(groups[1]), core_bits);
    for (int k = 0; k < 3; ++k) body_size += part_size(basis_count[k], ranks[k], basis_bits);
    const std::size_t payload = r.expect_payload();
    Bytes inflated;
    const std::uint8_t* body = r.here();
    if (pk == Packing::Deflated) {
        inflated = inflate_bytes(r.here(), payload, static_cast<std::size_t>(body_size), kTuckerSource);
        body = inflated.data();
    } else if (body_size != payload) {
        r.fail("payload of " + std::to_string(payload) + " bytes, expected " + std::to_string(body_size) +
               " for the stated dimensions, ranks and bits");
    }
    detail::ByteReader br(body, static_cast<std::size_t>(body_size), kTuckerSource);
    tensor::TuckerModel m;
    m.ranks = rk;
    m.method = static_cast<tensor::TuckerMethod>(method);
    m.core = Tensor3(rk[0], rk[1], rk[2]);
    Eigen::Map<MatX>(m.core.data(), groups[0], groups[1]) =
        dequantize(read_part(br, groups[0], groups[1], core_bits, pk));
    for (int k = 0; k < 3; ++k)
        m.U[k] = dequantize(read_part(br, static_cast<Eigen::Index>(dims[k]), rk[k], basis_bits, pk));
    br.expect_end();
    return m;
}

tensor::TuckerModel decode_quantized_tucker(const Bytes& stream) {
    return decode_quantized_tucker(stream.data(), stream.size());
}

std::size_t packed_tucker_bytes(const tensor::Dims3& dims, const tensor::Ranks& ranks,
                                const QuantizeTuckerOptions& options) {
    check_bits(options.core_bits, "packed_tucker_bytes (core_bits)");
    check_bits(options.basis_bits, "packed_tucker_bytes (basis_bits)");
    tensor::check_ranks(dims, ranks, "packed_tucker_bytes");
    const auto groups = core_groups(ranks, options.core_grouping);
    auto u = [](Eigen::Index v) { return static_cast<std::uint64_t>(v); };
    std::uint64_t total = 8 * u(groups[1]) + packed_code_bytes(u(groups[0] * groups[1]), options.core_bits);
    for (int k = 0; k < 3; ++k) total += 8 * u(ranks[k]) + packed_code_bytes(u(dims[k] * ranks[k]), options.basis_bits);
    return static_cast<std::size_t>(total);
}

}  // namespace mocapdb::compression::codecs
