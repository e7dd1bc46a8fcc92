// The bad-input corpus (tests/bad_inputs/cases.tsv, docs/reliability.md): every case runs the
// real `shatter` binary on a broken mesh, shot, batch file, stage file or PNG, and must end with
// its documented exit code, a message that names the problem, and, when it fails, no file at all
// in its output folder (no partial output). One test per case, so ctest runs them in parallel.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

namespace fs = std::filesystem;
using testing_support::run_shatter;
using testing_support::TempDir;

const std::string kInputs = std::string(SHATTER_SOURCE_DIR) + "/tests/bad_inputs";

struct Case {
    std::string name;
    int exit_code = 0;
    std::string message;
    std::string command;
    std::string allowed_leftover;  // a file a failed case may leave (a known deviation), or ""
};

std::vector<Case> read_cases() {
    std::vector<Case> cases;
    std::ifstream in(kInputs + "/cases.tsv");
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> f;
        std::stringstream s(line);
        for (std::string field; std::getline(s, field, '\t');) f.push_back(field);
        if (f.size() != 4 && f.size() != 5) {
            ADD_FAILURE() << "cases.tsv: a line without 4 or 5 tab-separated fields: " << line;
            continue;
        }
        cases.push_back({f[0], std::stoi(f[1]), f[2], f[3], f.size() == 5 ? f[4] : ""});
    }
    return cases;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
    for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
    return s;
}

// A binary STL of `triangles` random triangles in the unit cube whose last vertex is NaN: millions
// of triangles that prescore must read and then refuse, without committing 100 MB.
std::string write_big_stl(const std::string& path, uint32_t triangles) {
    std::ofstream out(path, std::ios::binary);
    char header[80] = {};
    out.write(header, 80);
    out.write(reinterpret_cast<const char*>(&triangles), 4);
    std::vector<char> record(50, 0);
    uint32_t state = 12345;
    for (uint32_t t = 0; t < triangles; ++t) {
        float v[12] = {};
        for (int i = 3; i < 12; ++i) {
            state = state * 1664525u + 1013904223u;
            v[i] = float(state >> 8) / float(1 << 24);
        }
        if (t + 1 == triangles) v[11] = std::nanf("");
        std::memcpy(record.data(), v, 48);
        out.write(record.data(), 50);
    }
    return path;
}

std::vector<std::string> split_args(const std::string& command) {
    std::vector<std::string> args;
    std::stringstream s(command);
    for (std::string a; s >> a;) args.push_back(a);
    return args;
}

std::vector<std::string> files_under(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (!e.is_directory()) out.push_back(fs::relative(e.path(), dir).string());
    return out;
}

class BadInputCorpus : public ::testing::TestWithParam<Case> {};

TEST_P(BadInputCorpus, EndsWithItsExitCodeAMessageAndNoPartialOutput) {
    const Case& c = GetParam();
    TempDir tmp;
    const fs::path out = tmp.path() / "out";
    fs::create_directories(out);
    std::string command = replace_all(c.command, "{in}", kInputs);
    command = replace_all(command, "{fixtures}", std::string(SHATTER_SOURCE_DIR) + "/tests/fixtures");
    command = replace_all(command, "{out}", out.string());
    if (command.find("{big}") != std::string::npos)
        command = replace_all(command, "{big}", write_big_stl(tmp.file("big.stl"), 2'000'000));
    if (command.find("{fifo}") != std::string::npos) {
        // A named pipe nobody writes to: reading it would wait forever.
        const std::string fifo = tmp.file("pipe");
        ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
        command = replace_all(command, "{fifo}", fifo);
    }
    const auto r = run_shatter(split_args(command), tmp.path().string());
    EXPECT_EQ(r.exit_code, c.exit_code) << "shatter " << command << "\nstderr:\n" << r.err;
    EXPECT_NE((r.err + r.out).find(c.message), std::string::npos)
        << "expected the output to contain '" << c.message << "'\nstderr:\n" << r.err;
    if (c.exit_code != 0) {
        std::vector<std::string> left = files_under(out);
        std::erase(left, c.allowed_leftover);
        EXPECT_TRUE(left.empty()) << "a failed command left " << left.size() << " files, e.g. " << left.front();
    }
    // A user's bad input is never a crash or an internal error (exit 70, or a signal).
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
    std::string n = info.param.name;
    for (char& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    return n;
}

INSTANTIATE_TEST_SUITE_P(Cases, BadInputCorpus, ::testing::ValuesIn(read_cases()), case_name);

TEST(BadInputCorpusManifest, HasAtLeastThirtyCasesWithUniqueNames) {
    const std::vector<Case> cases = read_cases();
    EXPECT_GE(cases.size(), 30u);
    std::set<std::string> names;
    for (const Case& c : cases) EXPECT_TRUE(names.insert(c.name).second) << "duplicate case " << c.name;
}

}  // namespace
}  // namespace shatter
