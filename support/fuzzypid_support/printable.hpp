// Outside input quoted in a message, made safe to print: a binary file's bytes must not reach the
// user's terminal raw (control characters move the cursor, change colours or ring the bell;
// invalid UTF-8 shows as garbage). Standard library only; private like the rest of support/.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "fuzzypid_support/utf8.hpp"

namespace fuzzypid::support {

// `text` with every control character (below 0x20, and DEL) and every byte that is not part of a
// well-formed UTF-8 sequence written as `\xHH`. Printable ASCII and valid UTF-8 (`café`) are kept
// as written.
inline std::string printable(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  const auto escape = [&out](unsigned char c) {
    out += "\\x";
    out += kHex[c >> 4];
    out += kHex[c & 0xf];
  };
  for (std::size_t k = 0; k < text.size();) {
    const auto c = static_cast<unsigned char>(text[k]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
      ++k;
      continue;
    }
    // A control character (a one-byte sequence here) or a byte outside well-formed UTF-8.
    const std::size_t n = c < 0x80 ? 0 : utf8_sequence_length(text, k);
    if (n == 0) {
      escape(c);
      ++k;
      continue;
    }
    out.append(text.substr(k, n));
    k += n;
  }
  return out;
}

}  // namespace fuzzypid::support
