#pragma once
// Fixtures of the codec tests: synthetic tensors, an independent CRC-32 (to forge streams whose
// checksum is right but whose content is wrong), a stream-mutation driver, and subject 16's walks as
// an aligned D x T x N tensor (built once per test executable).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "mocapdb/compression/codecs/encoded_stream.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "shared_data.hpp"

namespace mocapdb::test {

using compression::codecs::Bytes;

inline Tensor3 random_tensor3(Eigen::Index d0, Eigen::Index d1, Eigen::Index d2, unsigned seed, double sigma = 1.0) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> nd(0.0, sigma);
    Tensor3 a(d0, d1, d2);
    for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = nd(rng);
    return a;
}

/// Smooth in time and across samples, like motion: sums of low-frequency sinusoids per dof.
inline Tensor3 smooth_tensor3(Eigen::Index D, Eigen::Index T, Eigen::Index N, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Tensor3 a(D, T, N);
    for (Eigen::Index d = 0; d < D; ++d) {
        const double amp = 3.0 * u(rng), phase = 3.0 * u(rng), freq = 1.0 + std::abs(u(rng)), off = 2.0 * u(rng);
        const double sample_phase = 0.3 * u(rng);
        for (Eigen::Index n = 0; n < N; ++n)
            for (Eigen::Index t = 0; t < T; ++t)
                a(d, t, n) = off + amp * std::sin(2.0 * kPi * freq * static_cast<double>(t) / static_cast<double>(T) + phase +
                                                  sample_phase * static_cast<double>(n)) +
                             0.1 * amp * std::cos(0.05 * static_cast<double>(n) + static_cast<double>(d));
    }
    return a;
}

inline double max_abs_diff(const Tensor3& a, const Tensor3& b) {
    REQUIRE(a.dimension(0) == b.dimension(0));
    REQUIRE(a.dimension(1) == b.dimension(1));
    REQUIRE(a.dimension(2) == b.dimension(2));
    double m = 0.0;
    for (Eigen::Index i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a.data()[i] - b.data()[i]));
    return m;
}

/// Bitwise CRC-32 (reflected polynomial 0xEDB88320), written independently of zlib.
/// Bytes in [begin, end) except the 4-byte window at skip.
inline std::uint32_t reference_crc32(const Bytes& b, std::size_t skip) {
    std::uint32_t c = 0xffffffffu;
    for (std::size_t i = 0; i < b.size(); ++i) {
        if (i >= skip && i < skip + 4) continue;
        c ^= b[i];
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return c ^ 0xffffffffu;
}

/// Rewrites the CRC-32 of a stream (the 4 bytes that end the header; it covers the header before
/// it and the payload), so that a mutated stream passes the checksum and reaches the decoder.
inline void fix_crc(Bytes& s, std::size_t header_bytes) {
    if (header_bytes < 4 || header_bytes > s.size()) return;
    const std::uint32_t c = reference_crc32(s, header_bytes - 4);
    for (std::size_t k = 0; k < 4; ++k) s[header_bytes - 4 + k] = static_cast<std::uint8_t>(c >> (8 * k));
}

/// Feeds a decoder every truncation of the stream, single-byte corruptions (with the checksum left
/// stale and with it fixed), and random multi-byte mutations with the checksum fixed. Each must
/// throw ParseError or decode; a decoded result is handed to `check` (e.g. "all finite").
/// Returns the number of ParseErrors seen.
inline int mutate_and_decode(const compression::codecs::EncodedStream& good, const std::function<void(const Bytes&)>& decode,
                             unsigned seed, int random_rounds = 300) {
    int errors = 0;
    auto attempt = [&](const Bytes& s) {
        try {
            decode(s);
        } catch (const ParseError& e) {
            ++errors;
            CHECK(std::string(e.what()).find("stream") != std::string::npos);
        }
    };
    const Bytes& b = good.bytes;
    const std::size_t step = std::max<std::size_t>(1, b.size() / 200);
    for (std::size_t len = 0; len < b.size(); len += (len < 64 ? 1 : step)) attempt(Bytes(b.begin(), b.begin() + len));
    std::mt19937 rng(seed);
    for (std::size_t i = 0; i < b.size(); i += (i < 64 ? 1 : step)) {
        Bytes s = b;
        s[i] ^= static_cast<std::uint8_t>(1u + rng() % 255u);
        attempt(s);
        if (i + 4 < good.header_bytes || i >= good.header_bytes) {
            fix_crc(s, good.header_bytes);
            attempt(s);
        }
    }
    for (int round = 0; round < random_rounds; ++round) {
        Bytes s = b;
        const int flips = 1 + static_cast<int>(rng() % 8u);
        for (int f = 0; f < flips; ++f) s[rng() % s.size()] = static_cast<std::uint8_t>(rng());
        fix_crc(s, good.header_bytes);
        attempt(s);
    }
    return errors;
}

/// Subject 16's walks (the clips of the Tucker issue) aligned by DTW to 100 frames: 90 x 100 x N.
/// Under sanitizers only the first 6 clips, to keep the suite fast.
inline const AlignedSet& subject16_walks_aligned() {
    static const AlignedSet aligned = [] {
        std::vector<Clip> clips;
        std::vector<std::string> trials;
        for (int t = 11; t <= 34; ++t) trials.push_back("16_" + std::to_string(t));
        trials.push_back("16_47");
#ifdef MOCAPDB_SANITIZED_BUILD
        trials.resize(6);
#endif
        for (const auto& t : trials) clips.push_back(read_clip(datasets_dir() / "cmu-asfamc" / (t + ".amc")));
        return align_samples(clips, AlignOptions{});
    }();
    return aligned;
}

}  // namespace mocapdb::test
