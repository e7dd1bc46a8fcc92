// check_ply_header: well-formed headers from common exporters pass; the header that crashed
// assimp (tests/fuzz/regressions/mesh/assimp-ply-header-segv.seed) and other malformed ones are
// refused with the line and the problem.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "meshio/ply_header.h"

namespace shatter {
namespace {

std::string problem(const std::string& bytes) {
    try {
        check_ply_header(bytes, "x.ply");
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        return e.what();
    }
    return "";
}

TEST(PlyHeader, HeadersOfCommonExportersPass) {
    EXPECT_EQ(problem("ply\nformat ascii 1.0\ncomment Created by Blender\nelement vertex 8\nproperty float x\n"
                      "property float y\nproperty float z\nelement face 6\nproperty list uchar uint vertex_indices\n"
                      "end_header\n1 2 3\n"), "");
    EXPECT_EQ(problem("ply\r\nformat binary_little_endian 1.0\r\nobj_info x\r\nelement vertex 0\r\n"
                      "property float32 x\r\n\r\nelement face 0\r\nproperty list uint8 int32 vertex_indices\r\n"
                      "end_header\r\n"), "");
    // Blender 2.47 writes its note as a bare line (assimp-testmodels' PLY/Wuson.ply); assimp skips it.
    EXPECT_EQ(problem("ply\nformat ascii 1.0\nCreated by Blender3D 247 - www.blender.org, source file: x\n"
                      "element vertex 8\nproperty float x\nend_header\n"), "");
    EXPECT_TRUE(looks_like_ply("ply\nformat"));
    EXPECT_TRUE(looks_like_ply("plyx"));  // assimp takes it for a PLY too: the strict check refuses it
    EXPECT_FALSE(looks_like_ply("# ply"));
}

TEST(PlyHeader, TheHeaderThatCrashedAssimpAndOtherDamageAreRefused) {
    const char raw[] = "ply\nformat binary_little_endian 1.0\neleme\0\0\0\0\0\0\0\0\0\0\x80?\n";
    const std::string crash(raw, sizeof raw - 1);
    EXPECT_NE(problem(crash).find("x.ply:3: the PLY header has a control or binary byte"), std::string::npos);
    EXPECT_NE(problem("ply\nformat ascii 1.0\nelement vertex 8\n").find("no end_header"), std::string::npos);
    // The header that made assimp spin for ever: "ply", a NUL, no end_header.
    const char spin[] = "ply\0format ascii 1.0\nelement vertex 8\nproperty float x\nend_header\n";
    EXPECT_NE(problem(std::string(spin, sizeof spin - 1)).find("x.ply:1:"), std::string::npos);
    EXPECT_NE(problem("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n").find("x.ply:3"), std::string::npos);
    EXPECT_NE(problem("ply\nformat ascii 1.0\nproperty float x\nend_header\n").find("before any element"),
              std::string::npos);
    EXPECT_NE(problem("ply\nformat ascii 1.0\nelement v 1\nproperty real x\nend_header\n").find("x.ply:4"),
              std::string::npos);
    EXPECT_NE(problem("ply\nelement v 1\nend_header\n").find("no format line"), std::string::npos);
    EXPECT_NE(problem("ply\nformat ebcdic 1.0\nend_header\n").find("format line"), std::string::npos);
}

}  // namespace
}  // namespace shatter
