// A strict check of a PLY file's header before assimp reads it.
//
// Debian's assimp 5.2 reads past its buffer on some malformed PLY headers and crashes (found by
// tests/fuzz/mesh_fuzz.cpp: a 153-byte file whose header stops inside an "element" line made
// `shatter prescore` die with SIGSEGV; regression inputs in tests/fuzz/regressions/mesh/ and
// tests/bad_inputs/). So a file that starts like a PLY ("ply" on the first line) must have a header
// that follows the format (http://paulbourke.net/dataformats/ply/): printable text lines, "format"
// ascii | binary_little_endian | binary_big_endian 1.0, "element NAME COUNT", "property TYPE NAME"
// or "property list TYPE TYPE NAME" with PLY's scalar types, and "end_header" within the first
// 64 kB. Other lines of printable text ("comment", "obj_info", an exporter's "Created by ...")
// are skipped, as assimp skips them. Anything else is refused with the line and what is wrong.
#pragma once

#include <string>
#include <string_view>

namespace shatter {

// True when `bytes` start like a PLY file: with "ply", as assimp's reader takes it (whatever
// follows: a file starting "ply\0format ascii ..." with no end_header made assimp 5.2 spin for
// ever; found by the fuzz smoke in CI, tests/fuzz/regressions/mesh/ply-nul-after-magic-hang.seed).
bool looks_like_ply(std::string_view bytes);

// Throws Error(BadInput) naming `path`, the header line and the problem.
void check_ply_header(std::string_view bytes, const std::string& path);

}  // namespace shatter
