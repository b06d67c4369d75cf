// Error messages quote what files hold (ids, names, values): printable() (core/error.h) keeps
// them one harmless line on a terminal, and every InputError's message goes through it.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"

namespace kasha {
namespace {

TEST(ErrorText, ControlCharactersAreEscaped) {
  // C0 (ESC, BEL, newline, tab, NUL) and DEL.
  EXPECT_EQ(printable(std::string("a\x1b[2J\x07\n\tb\x7f", 10) + std::string(1, '\0')),
            "a\\x1b[2J\\x07\\x0a\\x09b\\x7f\\x00");
  // C1 in its UTF-8 form: U+009B (CSI) is C2 9B.
  EXPECT_EQ(printable("x\xc2\x9b" "31m"), "x\\xc2\\x9b31m");
  // Bytes that are not well-formed UTF-8: a lone continuation byte, a raw 8-bit CSI, a cut
  // sequence, an overlong encoding, a surrogate.
  EXPECT_EQ(printable("\x80"), "\\x80");
  EXPECT_EQ(printable("\x9b"), "\\x9b");
  EXPECT_EQ(printable("\xe2\x82"), "\\xe2\\x82");
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");
}

TEST(ErrorText, PrintableTextIsKept) {
  for (const std::string s : {"scene.xml:3: bsdf 'diffuse': value '1,5' is not a number", "λ = 550 nm, 25 °C, Å",
                              "\xf0\x9f\x99\x82 \xc2\xa0", "back\\slash \\x1b stays"})
    EXPECT_EQ(printable(s), s);
  // Escaping twice changes nothing (a message re-composed from another is not escaped again).
  const std::string once = printable("\x1b\x07\xff");
  EXPECT_EQ(printable(once), once);
}

TEST(ErrorText, InputErrorMessagesArePrintable) {
  const InputError e("m\x1b.xml:2", "id '\x07'", "no such \x1b[31mthing");
  EXPECT_STREQ(e.what(), "m\\x1b.xml:2: id '\\x07': no such \\x1b[31mthing");
  EXPECT_EQ(e.field(), "id '\x07'");  // the parts stay as given, for front ends that re-compose them
}

}  // namespace
}  // namespace kasha
