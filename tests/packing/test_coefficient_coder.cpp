#include <catch2/catch.hpp>

#include <random>

#include "mocapdb/packing/coefficient_coder.hpp"
#include "mocapdb/packing/range_coder.hpp"

using namespace mocapdb::packing;

TEST_CASE("range coder round-trips adaptive and direct bits", "[packing][range_coder]") {
    std::mt19937 rng(3);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = trial * 37;
        std::vector<int> bits(n), direct(n);
        std::vector<BitContext> enc_ctx(4, kProbabilityHalf), dec_ctx(4, kProbabilityHalf);
        RangeEncoder enc;
        for (int i = 0; i < n; ++i) {
            bits[i] = static_cast<int>(rng() % 10) < trial % 10 ? 1 : 0;
            direct[i] = static_cast<int>(rng() % 4096);
            enc.encode(enc_ctx[i % 4], bits[i]);
            enc.encode_direct(static_cast<std::uint32_t>(direct[i]), 12);
        }
        const auto bytes = enc.finish();
        RangeDecoder dec(bytes.data(), bytes.size());
        for (int i = 0; i < n; ++i) {
            REQUIRE(dec.decode(dec_ctx[i % 4]) == bits[i]);
            REQUIRE(static_cast<int>(dec.decode_direct(12)) == direct[i]);
        }
    }
}

TEST_CASE("coefficient coder round-trips a window, trained contexts code it smaller", "[packing][coefficient_coder]") {
    std::mt19937 rng(5);
    const std::size_t n = 600;
    std::vector<float> sigma(n);
    for (std::size_t i = 0; i < n; ++i) sigma[i] = 1000.0f / static_cast<float>(1 + i);
    std::vector<std::uint8_t> classes;
    position_classes(class_levels(sigma), 1.0, classes);
    ContextCounts counts;
    const std::vector<std::uint32_t> scan = identity_scan(n);
    const ScanGrid grid{&scan, 20};
    std::vector<std::vector<std::int32_t>> windows;
    for (int w = 0; w < 30; ++w) {
        std::vector<std::int32_t> q(n, 0);
        for (std::size_t i = 0; i < n; ++i) {
            std::normal_distribution<double> g(0.0, sigma[i]);
            q[i] = static_cast<std::int32_t>(std::lround(g(rng)));
        }
        q[1] = 3000000;  // a long gamma code
        q[n - 1] = 0;
        windows.push_back(q);
        count_coefficients(q, classes, grid, counts);
    }
    const ContextSet trained = counts.to_contexts();
    std::size_t plain_bytes = 0, trained_bytes = 0;
    for (const auto& q : windows) {
        for (const ContextSet& ctx : {ContextSet(), trained}) {
            const auto bytes = encode_coefficients(q, classes, grid, ctx);
            std::vector<std::int32_t> back;
            decode_coefficients(bytes.data(), bytes.size(), classes, grid, ctx, back);
            REQUIRE(back == q);
            (&ctx == &trained ? trained_bytes : plain_bytes) += bytes.size();
        }
    }
    INFO("plain " << plain_bytes << " B, trained " << trained_bytes << " B");
    CHECK(trained_bytes < plain_bytes);
    std::vector<std::int32_t> zeros(n, 0), back;
    const auto empty = encode_coefficients(zeros, classes, grid, trained);
    decode_coefficients(empty.data(), empty.size(), classes, grid, trained, back);
    CHECK(back == zeros);
    CHECK(empty.size() <= 1);
}
