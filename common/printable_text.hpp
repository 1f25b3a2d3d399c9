// Text from outside (a command's names and values, a client id, a key name, a string on the bus),
// made fit to quote in an answer, a log line or on a terminal: no byte of it can drive a terminal
// (control bytes and the like become \xNN), and an echo is cut to a bounded length, so that a
// 64 KiB value echoed into an ACK's reason takes a line, not the bus.
//
//   PrintableText   printable ASCII only, cut to max_length with "...": what the server echoes
//   TerminalText    printable ASCII and well-formed UTF-8 characters but control characters, not
//                   cut: what flagctl prints of a message from the bus
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace flagsim {

/// Characters of a name or value an answer quotes, at most (escapes included, "..." not).
constexpr size_t kEchoLength = 64;

/// `text` with each byte that is not printable ASCII (0x20 .. 0x7e) as \xNN; when that is longer
/// than `max_length` characters, its first whole characters and escapes within `max_length`
/// followed by "...".
std::string PrintableText(std::string_view text, size_t max_length = kEchoLength);

/// `text` for a terminal: printable ASCII and well-formed UTF-8 characters are kept; control
/// characters (C0, DEL, C1: U+0000 .. U+001F, U+007F .. U+009F, newlines and escapes too) and
/// bytes that are not UTF-8 become \xNN, one escape per byte.
std::string TerminalText(std::string_view text);

}  // namespace flagsim
