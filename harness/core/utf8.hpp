#pragma once
// Well-formed UTF-8 (RFC 3629), for quoting user text in messages and in meta.json.
#include <cstddef>
#include <string_view>

namespace dabench {

// Length of the well-formed multi-byte UTF-8 sequence at text[at] (no overlongs, no surrogates,
// at most U+10FFFF), or 0 (an ASCII byte, or bytes that are not UTF-8).
inline std::size_t utf8_length(std::string_view text, std::size_t at) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[at + k]); };
  const unsigned char lead = byte(0);
  const std::size_t length = lead >= 0xC2 && lead <= 0xDF ? 2 : lead >= 0xE0 && lead <= 0xEF ? 3
                             : lead >= 0xF0 && lead <= 0xF4 ? 4 : 0;
  if (length == 0) return 0;
  // The second byte's range (the rest are 0x80..0xBF): E0 and F0 exclude overlongs, ED the
  // surrogates, F4 what lies beyond U+10FFFF.
  const unsigned char low = lead == 0xE0 ? 0xA0 : lead == 0xF0 ? 0x90 : 0x80;
  const unsigned char high = lead == 0xED ? 0x9F : lead == 0xF4 ? 0x8F : 0xBF;
  if (at + length > text.size()) return 0;
  if (byte(1) < low || byte(1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k) {
    if (byte(k) < 0x80 || byte(k) > 0xBF) return 0;
  }
  return length;
}

}  // namespace dabench
