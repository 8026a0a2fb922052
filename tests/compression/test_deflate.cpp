#include <catch2/catch.hpp>

#include "codec_fixtures.hpp"
#include "mocapdb/compression/codecs/deflate.hpp"

using namespace mocapdb;
using namespace mocapdb::compression::codecs;

TEST_CASE("deflate round-trips byte buffers", "[codec][deflate]") {
    std::mt19937 rng(7);
    Bytes random(5000), zeros(100000, 0), empty;
    for (auto& b : random) b = static_cast<std::uint8_t>(rng());
    for (const Bytes* in : {&random, &zeros, &empty}) {
        const Bytes z = deflate_bytes(*in);
        CHECK(inflate_bytes(z.data(), z.size(), in->size()) == *in);
    }
    CHECK(deflate_bytes(zeros).size() < 200);       // 100 kB of zeros
    CHECK(deflate_bytes(random).size() > 4900);     // random bytes do not compress
    CHECK(deflate_bytes(random, 0).size() > random.size());  // stored blocks
    CHECK_THROWS_AS(deflate_bytes(random, 10), InvalidArgument);

    const Bytes z = deflate_bytes(random);
    CHECK_THROWS_AS(inflate_bytes(z.data(), z.size(), random.size() - 1), ParseError);
    CHECK_THROWS_AS(inflate_bytes(z.data(), z.size(), random.size() + 1), ParseError);
    CHECK_THROWS_AS(inflate_bytes(z.data(), z.size() - 1, random.size()), ParseError);  // Adler-32 cut
    Bytes longer = z;
    longer.push_back(0);
    CHECK_THROWS_AS(inflate_bytes(longer.data(), longer.size(), random.size()), ParseError);
    // A tiny stream claiming a huge output is refused before allocating it.
    CHECK_THROWS_AS(inflate_bytes(z.data(), 10, std::size_t{1} << 31), ParseError);
    try {
        Bytes bad = z;
        bad[z.size() / 2] ^= 0x55;
        inflate_bytes(bad.data(), bad.size(), random.size(), "my stream");
        FAIL("a corrupted stream decoded");
    } catch (const ParseError& e) {
        CHECK(e.file() == "my stream");
    }
}

TEST_CASE("lossless float32 baseline reproduces the float32 image exactly", "[codec][deflate]") {
    const Tensor3 smooth = test::smooth_tensor3(30, 100, 12, 3);
    const Tensor3 noisy = test::random_tensor3(17, 9, 5, 4);
    for (const Tensor3* a : {&smooth, &noisy}) {
        for (bool shuffle : {true, false}) {
            Float32DeflateOptions options;
            options.shuffle = shuffle;
            const EncodedStream s = encode_float32_deflate(*a, options);
            const Tensor3 back = decode_float32_deflate(s.bytes);
            const Tensor3 image = round_to_float32(*a);
            REQUIRE(back.dimension(0) == a->dimension(0));
            REQUIRE(back.dimension(2) == a->dimension(2));
            CHECK(test::max_abs_diff(back, image) == 0.0);  // bit-exact float32 values
            // Accounting: header + payload is the stream, and the payload is one zlib stream of the
            // 4 D T N byte image (decodable on its own).
            CHECK(s.header_bytes + s.payload_bytes() == s.bytes.size());
            CHECK(s.header_bytes == 4 + 1 + 1 + 12 + 8 + 4);
            CHECK_NOTHROW(inflate_bytes(s.bytes.data() + s.header_bytes, s.payload_bytes(),
                                        static_cast<std::size_t>(4 * a->size())));
            CHECK(encode_float32_deflate(*a, options).bytes == s.bytes);  // deterministic
        }
    }
    const auto smooth_bytes = encode_float32_deflate(smooth).payload_bytes();
    INFO("smooth 30x100x12 float32: raw " << 4 * smooth.size() << " B, shuffled deflate " << smooth_bytes << " B");
    CHECK(smooth_bytes < static_cast<std::size_t>(4 * smooth.size()));
}

TEST_CASE("lossless float32 baseline refuses bad input and bad streams", "[codec][deflate]") {
    Tensor3 a = test::random_tensor3(4, 5, 3, 9);
    CHECK_THROWS_AS(encode_float32_deflate(Tensor3(0, 3, 3)), InvalidArgument);
    a(1, 2, 0) = std::nan("");
    CHECK_THROWS_AS(encode_float32_deflate(a), InvalidArgument);
    a(1, 2, 0) = 1e300;  // finite in double, not in float32
    CHECK_THROWS_AS(encode_float32_deflate(a), InvalidArgument);
    a(1, 2, 0) = 0.5;
    const EncodedStream good = encode_float32_deflate(a);
    const int errors = test::mutate_and_decode(good, [](const Bytes& s) {
        const Tensor3 t = decode_float32_deflate(s);
        for (Eigen::Index i = 0; i < t.size(); ++i) REQUIRE(std::isfinite(t.data()[i]));
    }, 11);
    CHECK(errors > 0);
    Bytes wrong = good.bytes;
    wrong[0] = 'X';
    CHECK_THROWS_WITH(decode_float32_deflate(wrong), Catch::Contains("magic"));
    Bytes cut(good.bytes.begin(), good.bytes.end() - 3);
    CHECK_THROWS_WITH(decode_float32_deflate(cut), Catch::Contains("truncated"));
}

TEST_CASE("stream checksums: the test's independent CRC-32 agrees with the encoder's", "[codec][deflate]") {
    const EncodedStream s = encode_float32_deflate(test::random_tensor3(3, 4, 5, 12));
    Bytes copy = s.bytes;
    test::fix_crc(copy, s.header_bytes);
    CHECK(copy == s.bytes);
    copy.back() ^= 1;
    CHECK_THROWS_WITH(decode_float32_deflate(copy), Catch::Contains("checksum mismatch"));
}
