#include "text_scanner.hpp"

#include <charconv>
#include <cmath>

namespace mocapdb::detail {

std::string quoted(std::string_view token) {
    std::string out = "'";
    const std::size_t limit = 40;
    for (std::size_t i = 0; i < token.size() && i < limit; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        if (c < 32 || c >= 127) {
            static const char hex[] = "0123456789abcdef";
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        } else {
            out += static_cast<char>(c);
        }
    }
    if (token.size() > limit) out += "...";
    return out + "'";
}

void TextScanner::skip_blanks() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r')) ++pos_;
}

void TextScanner::skip_whitespace() {
    for (;;) {
        skip_blanks();
        if (pos_ < text_.size() && text_[pos_] == '\n') {
            ++pos_;
            ++line_;
            line_start_ = pos_;
        } else {
            return;
        }
    }
}

bool TextScanner::at_end() {
    skip_whitespace();
    return pos_ >= text_.size();
}

bool TextScanner::at_line_end() {
    skip_blanks();
    return pos_ >= text_.size() || text_[pos_] == '\n';
}

void TextScanner::next_line() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    if (pos_ < text_.size()) {
        ++pos_;
        ++line_;
        line_start_ = pos_;
    }
}

std::string_view TextScanner::rest_of_line() {
    skip_blanks();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    std::size_t end = pos_;
    while (end > start && (text_[end - 1] == '\r' || text_[end - 1] == ' ' || text_[end - 1] == '\t')) --end;
    next_line();
    return text_.substr(start, end - start);
}

std::string_view TextScanner::token_on_line() {
    skip_blanks();
    token_line_ = line_;
    token_column_ = column();
    const std::size_t start = pos_;
    while (pos_ < text_.size()) {
        const char c = text_[pos_];
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n') break;
        ++pos_;
    }
    return text_.substr(start, pos_ - start);
}

std::string_view TextScanner::token() {
    skip_whitespace();
    return token_on_line();
}

std::string_view TextScanner::peek_token() {
    const std::size_t pos = pos_, line = line_, line_start = line_start_, tl = token_line_, tc = token_column_;
    const std::string_view t = token();
    pos_ = pos;
    line_ = line;
    line_start_ = line_start;
    token_line_ = tl;
    token_column_ = tc;
    return t;
}

void TextScanner::expect(std::string_view expected) {
    const std::string_view t = token();
    if (t != expected) {
        fail_at_token("expected '" + std::string(expected) + "', found " +
                      (t.empty() ? std::string("end of file") : quoted(t)));
    }
}

double TextScanner::to_number(std::string_view t, std::string_view what) const {
    if (t.empty())
        fail("expected " + std::string(what) + " (a number), found " +
             (pos_ >= text_.size() ? "end of file" : "end of line"));
    const char* first = t.data();
    const char* last = t.data() + t.size();
    if (*first == '+') ++first;  // from_chars refuses a leading '+', which some exporters write
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec == std::errc::result_out_of_range) fail_at_token(std::string(what) + " " + quoted(t) + " is out of range");
    if (ec != std::errc() || ptr != last)
        fail_at_token("expected " + std::string(what) + " (a number), found " + quoted(t));
    if (!std::isfinite(value)) fail_at_token(std::string(what) + " " + quoted(t) + " is not finite");
    if (std::abs(value) > kMaxAbsValue)
        fail_at_token(std::string(what) + " " + quoted(t) + " is absurdly large (|value| > 1e9)");
    return value;
}

double TextScanner::number(std::string_view what) { return to_number(token(), what); }

double TextScanner::number_on_line(std::string_view what) { return to_number(token_on_line(), what); }

long long TextScanner::integer(std::string_view what) {
    const std::string_view t = token();
    long long value = 0;
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (t.empty() || ec != std::errc() || ptr != t.data() + t.size() || value < 0)
        fail_at_token("expected " + std::string(what) + " (a non-negative integer), found " +
                      (t.empty() ? std::string("end of file") : quoted(t)));
    return value;
}

void TextScanner::fail(const std::string& message) const { throw ParseError(name_, line_, column(), message); }

void TextScanner::fail_at_token(const std::string& message) const {
    throw ParseError(name_, token_line_, token_column_, message);
}

}  // namespace mocapdb::detail
