// Well-formed UTF-8 (RFC 3629), byte by byte: the one definition printable() and the readers that
// must refuse malformed text share. Standard library only; private like the rest of support/.
#pragma once

#include <cstddef>
#include <string_view>

namespace fuzzypid::support {

// The length (1 to 4) of the well-formed UTF-8 sequence that starts at text[at], or 0 when none
// does there: a stray continuation byte, a lead byte without all its continuation bytes (also
// when the text ends first), an overlong form, a surrogate or a code point above U+10FFFF.
inline std::size_t utf8_sequence_length(std::string_view text, std::size_t at) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char c = byte(at);
  if (c < 0x80) return 1;
  std::size_t length = 0;
  unsigned char lo = 0x80, hi = 0xbf;  // the allowed range of the second byte
  if (c >= 0xc2 && c <= 0xdf) {
    length = 2;
  } else if (c >= 0xe0 && c <= 0xef) {
    length = 3;
    if (c == 0xe0) lo = 0xa0;  // overlong below U+0800
    if (c == 0xed) hi = 0x9f;  // surrogates U+D800..U+DFFF
  } else if (c >= 0xf0 && c <= 0xf4) {
    length = 4;
    if (c == 0xf0) lo = 0x90;  // overlong below U+10000
    if (c == 0xf4) hi = 0x8f;  // above U+10FFFF
  } else {
    return 0;
  }
  if (at + length > text.size() || byte(at + 1) < lo || byte(at + 1) > hi) return 0;
  for (std::size_t k = 2; k < length; ++k)
    if ((byte(at + k) & 0xc0) != 0x80) return 0;
  return length;
}

// The offset of the first byte of `text` that is not part of a well-formed UTF-8 sequence, or
// npos when it is UTF-8 throughout.
inline std::size_t first_invalid_utf8(std::string_view text) {
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t n = utf8_sequence_length(text, at);
    if (n == 0) return at;
    at += n;
  }
  return std::string_view::npos;
}

}  // namespace fuzzypid::support
