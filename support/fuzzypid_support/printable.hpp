// Outside input quoted in a message, made safe to print: a binary file's bytes must not reach the
// user's terminal raw (control characters move the cursor, change colours or ring the bell;
// invalid UTF-8 shows as garbage). Standard library only; private like the rest of support/.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

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
    // The length of a well-formed UTF-8 sequence starting here (0: none).
    std::size_t n = c >= 0xc2 && c <= 0xdf   ? 2
                    : c >= 0xe0 && c <= 0xef ? 3
                    : c >= 0xf0 && c <= 0xf4 ? 4
                                             : 0;
    if (n != 0 && k + n <= text.size()) {
      for (std::size_t j = 1; j < n; ++j)
        if ((static_cast<unsigned char>(text[k + j]) & 0xc0) != 0x80) n = 0;
    } else {
      n = 0;
    }
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
