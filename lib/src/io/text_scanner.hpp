#pragma once
// Internal: a cursor over text for the line-oriented mocap formats. Tracks line and column for
// errors, accepts LF and CRLF (and tabs), and parses numbers strictly and locale-independently.
#include <cstddef>
#include <string>
#include <string_view>

#include "mocapdb/core/error.hpp"

namespace mocapdb::detail {

/// Values beyond this magnitude are refused as corrupt (no mocap length or angle comes near it).
constexpr double kMaxAbsValue = 1e9;

class TextScanner {
public:
    TextScanner(std::string_view text, std::string source_name) : text_(text), name_(std::move(source_name)) {}

    /// Skips spaces, tabs and carriage returns, but not line feeds.
    void skip_blanks();
    /// Skips all whitespace including line feeds.
    void skip_whitespace();
    /// True at the end of the text (after skipping whitespace).
    bool at_end();
    /// True when only blanks remain on the current line.
    bool at_line_end();
    /// Moves past the next line feed (or to the end).
    void next_line();
    /// The rest of the current line without the trailing CR/LF, and moves past it.
    std::string_view rest_of_line();

    /// The next whitespace-delimited token (may cross lines); empty at end of text.
    std::string_view token();
    /// The next token on the current line; empty when the line has no more tokens.
    std::string_view token_on_line();
    /// Like token() but does not consume it.
    std::string_view peek_token();

    /// Reads a token and requires it to equal `expected` (ParseError otherwise).
    void expect(std::string_view expected);
    /// Parses a finite number no larger than kMaxAbsValue in magnitude; `what` names it in errors.
    double number(std::string_view what);
    double number_on_line(std::string_view what);
    /// Parses a non-negative integer.
    long long integer(std::string_view what);

    /// Parses `token` as a number with the same rules (for callers that already hold the token).
    double to_number(std::string_view token, std::string_view what) const;

    std::size_t line() const noexcept { return line_; }
    std::size_t column() const noexcept { return pos_ - line_start_ + 1; }
    const std::string& source_name() const noexcept { return name_; }

    [[noreturn]] void fail(const std::string& message) const;
    /// Error located at the start of the last token read.
    [[noreturn]] void fail_at_token(const std::string& message) const;
    std::size_t token_line() const noexcept { return token_line_; }

private:
    std::string_view text_;
    std::string name_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    std::size_t line_start_ = 0;
    std::size_t token_line_ = 1;
    std::size_t token_column_ = 1;
};

/// Quotes a token for an error message, truncated and with control characters escaped.
std::string quoted(std::string_view token);

}  // namespace mocapdb::detail
