// Lossless channel packing (mocapdb/packing/lossless_channels.hpp) on its own, without HDF5: decimal
// text parsed as the readers do decodes bit for bit, the decimal resolution is detected per channel,
// values without a decimal form (computed, -0, NaN, infinities) are kept exactly, and malformed
// packed data is refused rather than decoded to something else.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "mocapdb/core/error.hpp"
#include "mocapdb/packing/lossless_channels.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// A value as a reader makes it: the decimal text parsed, times the unit factor.
double read_as_reader(const std::string& text, double scale) { return std::strtod(text.c_str(), nullptr) * scale; }

// F frames of C smooth channels written as %g with 6 significant digits (as CMU's AMC files are),
// in degrees (channel 0 in source length units times 5.6444 cm).
FrameMatrix amc_like(int frames, int channels, std::vector<double>& scales) {
    FrameMatrix m(frames, channels);
    scales.assign(static_cast<std::size_t>(channels), kDegree);
    scales[0] = 2.54 / 0.45;
    char text[64];
    for (int t = 0; t < frames; ++t)
        for (int c = 0; c < channels; ++c) {
            // Channel 3 crosses zero (more decimals near it) and channel 4 is %g noise around 1e-14.
            const double v = c == 4 ? 1e-14 * std::sin(0.37 * t) : 40.0 * std::sin(0.01 * t * (c + 1) + c) + (c == 3 ? 0 : 5.0 * c);
            std::snprintf(text, sizeof text, "%g", v);
            m(t, c) = read_as_reader(text, scales[static_cast<std::size_t>(c)]);
        }
    return m;
}

}  // namespace

TEST_CASE("channel packing: %g decimal text decodes bit for bit and beats float32", "[store][packing]") {
    std::vector<double> scales;
    const FrameMatrix m = amc_like(600, 8, scales);
    const packing::PackedChannels p = packing::pack_channels(m, scales);
    CHECK(p.frames == 600);
    REQUIRE(p.channels() == 8);
    for (std::size_t c = 0; c < 8; ++c) {
        INFO("channel " << c);
        CHECK(p.decimals[c] != packing::kRawChannel);  // every channel was read from decimals
        CHECK((p.predictor[c] == 1 || p.predictor[c] == 2));
        CHECK(p.scale[c] == scales[c]);
    }
    CHECK(same_bits(packing::unpack_channels(p), m));
    const auto float32_bytes = static_cast<std::size_t>(m.size()) * 4;
    INFO("packed " << p.bytes.size() << " bytes, float32 " << float32_bytes);
    CHECK(p.bytes.size() < float32_bytes / 2);
}

TEST_CASE("channel packing: the base decimals follow the source resolution", "[store][packing]") {
    // Column 0 has two decimals, column 1 none, column 2 four; positions in cm (scale 1).
    FrameMatrix m(50, 3);
    char text[64];
    for (int t = 0; t < 50; ++t) {
        std::snprintf(text, sizeof text, "%.2f", 10.0 + 0.37 * t);
        m(t, 0) = read_as_reader(text, 1.0);
        m(t, 1) = static_cast<double>(3 * t - 40);
        std::snprintf(text, sizeof text, "%.4f", 1.0 + 0.0123 * t * t);
        m(t, 2) = read_as_reader(text, kDegree);
    }
    const packing::PackedChannels p = packing::pack_channels(m, {1.0, 1.0, kDegree});
    CHECK(p.decimals == std::vector<std::int64_t>{2, 0, 4});
    CHECK(p.predictor[1] == 2);  // a straight line: order 2 predicts it exactly (residuals 0)
    CHECK(same_bits(packing::unpack_channels(p), m));
}

TEST_CASE("channel packing: computed values, -0, NaN and infinities are kept exactly", "[store][packing]") {
    FrameMatrix m(200, 4);
    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0.0, 1.0);
    for (int t = 0; t < 200; ++t) {
        m(t, 0) = std::sin(0.05 * t) * 17.3 + 1e-3 * noise(rng);  // computed: no short decimal form
        m(t, 1) = t % 3 == 0 ? -0.0 : 0.5 * t;                   // BVH files write "-0.0"
        m(t, 2) = 0.25 * t;
        m(t, 3) = 1.5;
    }
    m(10, 2) = std::numeric_limits<double>::quiet_NaN();
    m(11, 2) = std::numeric_limits<double>::infinity();
    m(12, 2) = -std::numeric_limits<double>::infinity();
    m(13, 2) = std::sqrt(2.0);  // one value without a decimal form in a decimal channel
    m(0, 3) = std::numeric_limits<double>::denorm_min();
    const packing::PackedChannels p = packing::pack_channels(m, {1.0, 1.0, 1.0, 1.0});
    CHECK(p.decimals[0] == packing::kRawChannel);
    CHECK(p.decimals[1] != packing::kRawChannel);
    CHECK(p.decimals[2] != packing::kRawChannel);
    const FrameMatrix back = packing::unpack_channels(p);
    CHECK(same_bits(back, m));
    CHECK(std::signbit(back(0, 1)));
    CHECK(std::isnan(back(10, 2)));
}

TEST_CASE("channel packing: every predictor and level is exact, one frame works", "[store][packing]") {
    std::vector<double> scales;
    const FrameMatrix m = amc_like(97, 5, scales);
    for (const int predictor : {0, 1, 2})
        for (const int level : {1, 19}) {
            packing::LosslessOptions o;
            o.predictor = predictor;
            o.zstd_level = level;
            const packing::PackedChannels p = packing::pack_channels(m, scales, o);
            INFO("predictor " << predictor << " level " << level);
            if (predictor != 0)
                for (std::size_t c = 0; c < p.channels(); ++c)
                    if (p.decimals[c] != packing::kRawChannel) CHECK(p.predictor[c] == predictor);
            CHECK(same_bits(packing::unpack_channels(p), m));
        }
    const FrameMatrix one = m.topRows(1);
    CHECK(same_bits(packing::unpack_channels(packing::pack_channels(one, scales)), one));
}

TEST_CASE("channel packing: bad arguments and malformed packed data are refused", "[store][packing]") {
    std::vector<double> scales;
    const FrameMatrix m = amc_like(120, 5, scales);
    CHECK_THROWS_AS(packing::pack_channels(FrameMatrix(0, 5), scales), InvalidArgument);
    CHECK_THROWS_AS(packing::pack_channels(m, {1.0}), InvalidArgument);
    CHECK_THROWS_AS(packing::pack_channels(m, {1.0, 1.0, 0.0, 1.0, 1.0}), InvalidArgument);
    packing::LosslessOptions bad;
    bad.zstd_level = 0;
    CHECK_THROWS_AS(packing::pack_channels(m, scales, bad), InvalidArgument);

    const packing::PackedChannels good = packing::pack_channels(m, scales);
    {
        packing::PackedChannels p = good;
        p.bytes[p.bytes.size() / 2] ^= 0x5A;  // zstd's content checksum or the section parse fails
        CHECK_THROWS_AS(packing::unpack_channels(p), Error);
    }
    {
        packing::PackedChannels p = good;
        p.section_bytes[0] += 1;
        CHECK_THROWS_WITH(packing::unpack_channels(p), Catch::Contains("zstd frame"));
    }
    {
        packing::PackedChannels p = good;
        p.frames += 1;
        CHECK_THROWS_WITH(packing::unpack_channels(p), Catch::Contains("section sizes"));
    }
    {
        packing::PackedChannels p = good;
        p.predictor[2] = 3;
        CHECK_THROWS_WITH(packing::unpack_channels(p), Catch::Contains("channel 2: expected predictor 1 or 2, found 3"));
    }
    {
        packing::PackedChannels p = good;
        p.decimals.pop_back();
        CHECK_THROWS_WITH(packing::unpack_channels(p), Catch::Contains("expected 5 decimals"));
    }
}
