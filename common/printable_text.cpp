#include "common/printable_text.hpp"

#include <cstdint>

namespace flagsim {
namespace {

bool PrintableAscii(uint8_t byte) { return byte >= 0x20 && byte <= 0x7e; }

/// The four characters \x1b for the byte 0x1b.
std::string Escape(uint8_t byte) {
  constexpr char kHex[] = "0123456789abcdef";
  return {'\\', 'x', kHex[byte >> 4], kHex[byte & 0xf]};
}

/// Well-formed UTF-8 characters of two to four bytes, by their lead byte (RFC 3629, table 3-7 of
/// the Unicode standard): the range the second byte must lie in rules out overlong forms,
/// surrogates, code points above U+10FFFF and, here, the C1 controls U+0080 .. U+009F.
struct Utf8Lead {
  uint8_t first, last;  ///< lead bytes
  size_t length;        ///< bytes of the character
  uint8_t second_low, second_high;
};
constexpr Utf8Lead kUtf8Leads[] = {
    {0xc2, 0xc2, 2, 0xa0, 0xbf},  // U+00A0 .. U+00BF: not the C1 controls
    {0xc3, 0xdf, 2, 0x80, 0xbf},  // U+00C0 .. U+07FF
    {0xe0, 0xe0, 3, 0xa0, 0xbf},  // U+0800 .. U+0FFF: no overlong forms
    {0xe1, 0xec, 3, 0x80, 0xbf},  // U+1000 .. U+CFFF
    {0xed, 0xed, 3, 0x80, 0x9f},  // U+D000 .. U+D7FF: no surrogates
    {0xee, 0xef, 3, 0x80, 0xbf},  // U+E000 .. U+FFFF
    {0xf0, 0xf0, 4, 0x90, 0xbf},  // U+10000 .. U+3FFFF: no overlong forms
    {0xf1, 0xf3, 4, 0x80, 0xbf},  // U+40000 .. U+FFFFF
    {0xf4, 0xf4, 4, 0x80, 0x8f},  // U+100000 .. U+10FFFF: nothing above
};

/// The length in bytes of the well-formed UTF-8 character at `at` that is not a control; 0 when
/// none is there.
size_t Utf8CharacterAt(std::string_view text, size_t at) {
  const uint8_t lead = uint8_t(text[at]);
  for (const Utf8Lead& form : kUtf8Leads) {
    if (lead < form.first || lead > form.last) continue;
    if (at + form.length > text.size()) return 0;
    const uint8_t second = uint8_t(text[at + 1]);
    if (second < form.second_low || second > form.second_high) return 0;
    for (size_t k = 2; k < form.length; ++k)
      if ((uint8_t(text[at + k]) & 0xc0) != 0x80) return 0;  // 10xxxxxx
    return form.length;
  }
  return 0;
}

}  // namespace

// text => piece by piece (a byte, or its escape) => out, until the next piece would pass max_length.
std::string PrintableText(std::string_view text, size_t max_length) {
  std::string out;
  for (size_t at = 0; at < text.size(); ++at) {
    const uint8_t byte = uint8_t(text[at]);
    const std::string piece = PrintableAscii(byte) ? std::string(1, char(byte)) : Escape(byte);
    if (out.size() + piece.size() > max_length) return out + "...";
    out += piece;
  }
  return out;
}

// text => kept characters and \xNN escapes => out
std::string TerminalText(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t at = 0; at < text.size();) {
    const uint8_t byte = uint8_t(text[at]);
    const size_t length = PrintableAscii(byte) ? 1 : Utf8CharacterAt(text, at);
    if (length == 0) {
      out += Escape(byte);
      ++at;
    } else {
      out.append(text.substr(at, length));
      at += length;
    }
  }
  return out;
}

}  // namespace flagsim
