// Text from outside made fit to quote: in an answer or a log line (printable ASCII, cut with an
// ellipsis), and on a terminal (UTF-8 kept, every control character escaped).
#include "common/printable_text.hpp"

#include <gtest/gtest.h>

#include <string>

namespace flagsim {
namespace {

/// Whether `text` holds a byte a terminal would read as a control (C0 or DEL).
bool HasControlByte(const std::string& text) {
  for (const char c : text)
    if (uint8_t(c) < 0x20 || uint8_t(c) == 0x7f) return true;
  return false;
}

TEST(PrintableText, PrintableAsciiWithinTheLengthIsKeptAsItIs) {
  EXPECT_EQ(PrintableText("stiffness"), "stiffness");
  EXPECT_EQ(PrintableText(""), "");
  const std::string longest(kEchoLength, 'x');
  EXPECT_EQ(PrintableText(longest), longest);
}

TEST(PrintableText, OtherBytesAreEscaped) {
  EXPECT_EQ(PrintableText("a\x1b[2Jb"), "a\\x1b[2Jb");
  EXPECT_EQ(PrintableText(std::string("nul\0here", 8)), "nul\\x00here");
  EXPECT_EQ(PrintableText("line\nbreak\x7f"), "line\\x0abreak\\x7f");
  EXPECT_EQ(PrintableText("\xc3\xbc"), "\\xc3\\xbc");  // UTF-8 too: an answer is ASCII
}

TEST(PrintableText, LongTextIsCutWithAnEllipsisNeverInAnEscape) {
  const std::string huge(64 * 1024, 'v');
  EXPECT_EQ(PrintableText(huge), std::string(kEchoLength, 'v') + "...");
  EXPECT_EQ(PrintableText("abcdefgh", 5), "abcde...");
  // 3 characters and an escape of 4 fit in 7; the next escape would not.
  EXPECT_EQ(PrintableText("abc\x01\x02", 7), "abc\\x01...");
  EXPECT_EQ(PrintableText("abc\x01\x02", 8), "abc\\x01...");
  const std::string escaped = PrintableText(std::string(1000, '\x1b'));
  EXPECT_LE(escaped.size(), kEchoLength + 3);
  EXPECT_FALSE(HasControlByte(escaped));
}

TEST(TerminalText, KeepsPrintableAsciiAndUtf8) {
  EXPECT_EQ(TerminalText("stiffness: 1e9 is out of range"), "stiffness: 1e9 is out of range");
  EXPECT_EQ(TerminalText("Flagge \xc3\xbc \xe2\x82\xac \xf0\x9f\x9a\xa9"),
            "Flagge \xc3\xbc \xe2\x82\xac \xf0\x9f\x9a\xa9");
  const std::string long_text(100000, 'a');
  EXPECT_EQ(TerminalText(long_text), long_text);  // not cut
}

TEST(TerminalText, EscapesEveryControlAndWhatIsNotUtf8) {
  EXPECT_EQ(TerminalText("\x1b]0;owned\x07"), "\\x1b]0;owned\\x07");  // sets a terminal's title
  EXPECT_EQ(TerminalText("a\r\nb\tc\x7f"), "a\\x0d\\x0ab\\x09c\\x7f");
  EXPECT_EQ(TerminalText("\xc2\x9b"
                         "2J"),
            "\\xc2\\x9b2J");  // U+009B, CSI as a C1 control
  EXPECT_EQ(TerminalText("\x9b"
                         "2J"),
            "\\x9b2J");                                                 // a lone byte of it
  EXPECT_EQ(TerminalText("\xc0\xaf"), "\\xc0\\xaf");                    // an overlong '/'
  EXPECT_EQ(TerminalText("\xed\xa0\x80"), "\\xed\\xa0\\x80");           // a surrogate
  EXPECT_EQ(TerminalText("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");  // above U+10FFFF
  EXPECT_EQ(TerminalText("\xe2\x82"), "\\xe2\\x82");                    // cut short
  EXPECT_EQ(TerminalText("\xc2\xa0"), "\xc2\xa0");                      // U+00A0, just past the C1 controls
}

}  // namespace
}  // namespace flagsim
