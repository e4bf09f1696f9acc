// printable(): what a file says reaches the user's terminal on one line and as text. Issue 49, item 12:
// bytes of names that are not UTF-8 reached stderr raw; they are escaped, UTF-8 itself passes whole.
#include <gtest/gtest.h>

#include "core/error.h"

namespace cpgi {
namespace {

TEST(Printable, Utf8PassesWholeAndOtherBytesAreEscaped) {
  EXPECT_EQ(printable("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x8f\xa0"),
            "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x8f\xa0");
  EXPECT_EQ(printable("a\xff"
                      "b\xfe"),
            "a\\xffb\\xfe");
  EXPECT_EQ(printable("cut \xc3"), "cut \\xc3");            // a sequence cut short
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");           // an overlong '/'
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a surrogate
  EXPECT_EQ(printable("\xc2\x9b"
                      "31m"),
            "\\xc2\\x9b31m");  // C1 CSI, which terminals act on
  EXPECT_EQ(printable("\x1b[31m\nx\x7f"), "\\x1b[31m\\nx\\x7f");
  // A multi-byte character counts once against the length kept.
  EXPECT_EQ(printable("\xc3\xa9\xc3\xa9\xc3\xa9", 2), "\xc3\xa9\xc3\xa9... (6 characters)");
}

TEST(Printable, InputErrorsCarryNoRawBytes) {
  const InputError e("scene\xff.glb", "node 'n\xfe': bad");
  EXPECT_STREQ(e.what(), "scene\\xff.glb: node 'n\\xfe': bad");
}

}  // namespace
}  // namespace cpgi
