#pragma once
// Errors the library throws when it cannot produce a result (docs/status.md). Results that exist but are
// not exactly what was asked (a jittered factorization, a fit stopped at its limit) carry a status instead.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace mocapdb {

/// Base of every error the library throws; what() is a complete one-line message for a user.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A caller broke a documented precondition (shape mismatch, out-of-range option).
class InvalidArgument : public Error {
public:
    using Error::Error;
};

/// Malformed text input. what() reads "FILE:LINE:COLUMN: MESSAGE" (column omitted when 0).
class ParseError : public Error {
public:
    ParseError(std::string file, std::size_t line, std::size_t column, const std::string& message);

    const std::string& file() const noexcept { return file_; }
    std::size_t line() const noexcept { return line_; }
    std::size_t column() const noexcept { return column_; }
    /// The message without the location prefix.
    const std::string& message() const noexcept { return message_; }

private:
    std::string file_;
    std::size_t line_;
    std::size_t column_;
    std::string message_;
};

/// A computation the data or parameters make impossible: a covariance that is not positive definite
/// where no regularization applies (the result does not exist; nothing was wrong with the call itself).
class NumericalError : public Error {
public:
    using Error::Error;
};

/// A file could not be opened, read or written (the operating system's reason is in the message).
class IoError : public Error {
public:
    using Error::Error;
};

}  // namespace mocapdb
