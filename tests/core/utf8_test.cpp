// Names from input files as valid UTF-8 (core/utf8.h): valid text kept byte for byte, Latin-1
// bytes turned into their code points, control bytes into '?'.
#include <gtest/gtest.h>

#include "core/utf8.h"

namespace shatter {
namespace {

TEST(Utf8, ValidTextIsKept) {
    for (const char* s : {"", "Roof", "Terraind\xc3\xa6k", "\xe2\x82\xac 5", "\xf0\x9f\x90\x87 bunny"})
        EXPECT_EQ(to_utf8(s), s) << s;
}

// assimp-testmodels' OBJ/regr01.mtl names a material "Terraind\xe6k" (Latin-1 for "Terraindæk").
TEST(Utf8, Latin1BytesBecomeTheirCodePoints) {
    EXPECT_EQ(to_utf8("Terraind\xe6k"), "Terraind\xc3\xa6k");
    EXPECT_EQ(to_utf8("\xff"), "\xc3\xbf");
    EXPECT_EQ(to_utf8("a\x80"), "a\xc2\x80");
    // A lead byte without its continuation, an overlong '/', a surrogate: each byte on its own.
    EXPECT_EQ(to_utf8("\xc3("), "\xc3\x83(");
    EXPECT_EQ(to_utf8("\xc0\xaf"), "\xc3\x80\xc2\xaf");
    EXPECT_EQ(to_utf8("\xed\xa0\x80"), "\xc3\xad\xc2\xa0\xc2\x80");
}

TEST(Utf8, ControlBytesBecomeQuestionMarks) { EXPECT_EQ(to_utf8(std::string("a\0b\n", 4)), "a?b?"); }

// as_utf8: valid text kept whole, control characters too (a path may hold a newline); otherwise
// what to_utf8 makes of it.
TEST(Utf8, AsUtf8KeepsValidTextWholeAndMendsTheRest) {
    EXPECT_EQ(as_utf8("dir\nname \xc3\xa9.obj"), "dir\nname \xc3\xa9.obj");
    EXPECT_EQ(as_utf8("b\xe6r\n.obj"), to_utf8("b\xe6r\n.obj"));
    EXPECT_EQ(as_utf8("b\xe6r.obj"), "b\xc3\xa6r.obj");
    EXPECT_EQ(as_utf8(""), "");
}

}  // namespace
}  // namespace shatter
