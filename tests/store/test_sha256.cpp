// SHA-256 against the FIPS 180-4 examples and against sha256sum(1) on a real file.
#include <catch2/catch.hpp>

#include "mocapdb/store/sha256.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

TEST_CASE("sha256: standard test vectors", "[store][sha256]") {
    CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    CHECK(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
          "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
    // One million 'a': many blocks, fed in uneven pieces.
    Sha256 h;
    const std::string piece(997, 'a');
    std::size_t fed = 0;
    while (fed + piece.size() <= 1000000) {
        h.update(piece);
        fed += piece.size();
    }
    h.update(std::string(1000000 - fed, 'a'));
    CHECK(h.hex_digest() == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
    // Lengths around the padding boundary (55, 56, 63, 64 bytes) agree between one and many updates.
    for (std::size_t n : {55u, 56u, 63u, 64u, 65u, 119u, 120u}) {
        const std::string text(n, 'x');
        Sha256 parts;
        for (char c : text) parts.update(std::string_view(&c, 1));
        CHECK(parts.hex_digest() == sha256_hex(text));
    }
}

TEST_CASE("sha256: agrees with sha256sum on a shared clip", "[store][sha256][shared]") {
    const auto file = datasets_dir() / "cmu-asfamc" / "16_15.amc";
    MOCAPDB_REQUIRE_SHARED(file);
    const CommandResult r = run_command("sha256sum " + quoted(file.string()));
    REQUIRE(r.exit_code == 0);
    CHECK(r.output.substr(0, 64) == sha256_hex(file_bytes(file)));
}
