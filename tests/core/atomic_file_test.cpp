#include <gtest/gtest.h>

#include <sys/stat.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

TEST(AtomicFile, ReplacesTheTargetAndLeavesNoTemporaryFile) {
    TempDir dir;
    write_file_atomic(dir.file("out.bin"), "old");
    write_file_atomic(dir.file("out.bin"), "new");
    EXPECT_EQ(read_file(dir.file("out.bin")), "new");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.bin"});
}

TEST(AtomicFile, UnwritableDirectoryIsAnIoErrorAndKeepsTheOldFile) {
    if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
    TempDir dir;
    write_file_atomic(dir.file("out.bin"), "old");
    ::chmod(dir.path().c_str(), 0555);
    EXPECT_THROW(write_file_atomic(dir.file("out.bin"), "new"), Error);
    ::chmod(dir.path().c_str(), 0755);
    EXPECT_EQ(read_file(dir.file("out.bin")), "old");
}

TEST(AtomicFile, MissingDirectoryIsAnIoErrorNamingThePath) {
    try {
        write_file_atomic("/nonexistent-dir/out.bin", "x");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Io);
        EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/out.bin"), std::string::npos);
    }
}

}  // namespace
}  // namespace shatter
