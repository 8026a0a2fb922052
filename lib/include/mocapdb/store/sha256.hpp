#pragma once
// SHA-256, used to recognise a source file that was imported before. Computed by OpenSSL's EVP
// interface (Debian libssl-dev: a well-kept library instead of a hand-written digest).
//
// Errors: std::bad_alloc when OpenSSL cannot allocate its context, mocapdb::Error if it reports a failure.
// Threads: one object per thread; sha256_hex is thread-safe.
#include <memory>
#include <string>
#include <string_view>

namespace mocapdb {

/// Incremental SHA-256: update() any number of times, then hex_digest() once. Movable, not copyable.
class Sha256 {
public:
    Sha256();
    ~Sha256();
    Sha256(Sha256&&) noexcept;
    Sha256& operator=(Sha256&&) noexcept;
    Sha256(const Sha256&) = delete;
    Sha256& operator=(const Sha256&) = delete;

    void update(std::string_view bytes);
    /// The digest as 64 lowercase hex characters. The object must not be updated afterwards.
    std::string hex_digest();

private:
    struct Context;  // OpenSSL's digest context (no OpenSSL type in a public header)
    std::unique_ptr<Context> context_;
};

/// SHA-256 of `bytes` as 64 lowercase hex characters.
std::string sha256_hex(std::string_view bytes);

}  // namespace mocapdb
