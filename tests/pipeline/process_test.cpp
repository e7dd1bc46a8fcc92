// Child processes: exit codes and signals reported, output captured from both pipes without
// deadlock, stdin fed, environment and working directory set, and arguments that a shell would
// act on ($(...), backticks, ;, quotes, newlines) delivered as plain bytes with nothing run.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/error.h"
#include "pipeline/process.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Process, ExitCodesAreReported) {
    EXPECT_EQ(run_process({"/bin/true"}).exit_code, 0);
    EXPECT_EQ(run_process({"/bin/false"}).exit_code, 1);
    const ProcessResult r = run_process({"/bin/sh", "-c", "exit 3"});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_EQ(r.signal, 0);
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.describe(), "exit code 3");
}

TEST(Process, DeathBySignalIsReportedWithItsName) {
    const ProcessResult r = run_process({"/bin/sh", "-c", "kill -KILL $$"});
    EXPECT_EQ(r.exit_code, -1);
    EXPECT_EQ(r.signal, SIGKILL);
    EXPECT_EQ(r.describe(), "killed by signal 9 (Killed)");
}

TEST(Process, StdoutAndStderrAreCapturedApart) {
    const ProcessResult r = run_process({"/bin/sh", "-c", "echo out; echo err >&2"});
    EXPECT_EQ(r.out, "out\n");
    EXPECT_EQ(r.err, "err\n");
}

TEST(Process, MegabytesOnBothPipesAndStdinDoNotDeadlock) {
    // 3 MB through cat while it writes back: needs reading while writing.
    std::string input(3 << 20, '\0');
    for (size_t i = 0; i < input.size(); ++i) input[i] = char('a' + i % 26);
    ProcessOptions options;
    options.stdin_data = input;
    EXPECT_EQ(run_process({"/bin/cat"}, options).out, input);
    // 1 MB on stdout, then 1 MB on stderr: the child blocks on stderr if we only read stdout.
    const ProcessResult r = run_process({"/bin/sh", "-c", "head -c 1048576 /dev/zero; head -c 1048576 /dev/zero >&2"});
    EXPECT_EQ(r.out.size(), 1048576u);
    EXPECT_EQ(r.err.size(), 1048576u);
}

// A stdin fed piece by piece (encode's frames as render writes them): megabytes through cat, each
// write reading what cat writes back meanwhile; a child that stops reading makes write_stdin false.
TEST(Process, StdinStreamedInPiecesArrivesWholeAndAChildGoneIsSaid) {
    ProcessOptions options;
    options.stdin_stream = true;
    ChildProcess cat({"/bin/cat"}, options);
    std::string sent;
    for (int i = 0; i < 6; ++i) {
        const std::string piece(1 << 19, char('a' + i));
        EXPECT_TRUE(cat.write_stdin(piece));
        sent += piece;
    }
    EXPECT_EQ(cat.wait().out, sent);  // (wait closes stdin: cat ends)
    ChildProcess quits({"/bin/true"}, options);
    bool open = true;
    for (int i = 0; i < 64 && open; ++i) open = quits.write_stdin(std::string(1 << 16, 'x'));
    EXPECT_FALSE(open);
    EXPECT_EQ(quits.wait().exit_code, 0);
}

TEST(Process, ChildThatIgnoresItsStdinDoesNotKillUsWithSigpipe) {
    ProcessOptions options;
    options.stdin_data = std::string(4 << 20, 'x');
    EXPECT_EQ(run_process({"/bin/true"}, options).exit_code, 0);
}

TEST(Process, EnvironmentAdditionsReplaceAndAdd) {
    ProcessOptions options;
    options.env = {{"SHATTER_TEST_VALUE", "a b $(x) `y`"}, {"HOME", "/nowhere"}};
    const std::string out = run_process({"/usr/bin/env"}, options).out;
    EXPECT_NE(out.find("\nSHATTER_TEST_VALUE=a b $(x) `y`\n"), std::string::npos);
    EXPECT_NE(out.find("\nHOME=/nowhere\n"), std::string::npos);  // our additions come last
    EXPECT_EQ(out.find("\nHOME="), out.rfind("\nHOME="));  // one HOME only
}

TEST(Process, WorkingDirectoryWithHostileNameIsUsed) {
    TempDir tmp;
    const auto dir = tmp.path() / "we'ird $(touch x) ;dir\nnext";
    std::filesystem::create_directory(dir);
    ProcessOptions options;
    options.working_directory = dir.string();
    EXPECT_EQ(run_process({"/bin/pwd"}, options).out, std::filesystem::canonical(dir).string() + "\n");
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "x"));
}

TEST(Process, OutputFileGetsStdoutAndStderrAppended) {
    TempDir tmp;
    const std::string log = tmp.write("log.txt", "before\n");
    ProcessOptions options;
    options.output_file = log;
    for (int i = 0; i < 2; ++i) {
        const ProcessResult r = run_process({"/bin/sh", "-c", "echo out; echo err >&2"}, options);
        EXPECT_TRUE(r.ok());
        EXPECT_EQ(r.out, "");
    }
    EXPECT_EQ(slurp(log), "before\nout\nerr\nout\nerr\n");
}

TEST(Process, HostileArgumentArrivesUnchangedAndNothingRuns) {
    TempDir tmp;
    // Every trick a shell would act on, aimed at files in the working directory.
    const std::string hostile =
        "a b  'single' \"double\" $(touch dollar) `touch backtick`; touch semicolon && touch and | touch pipe "
        "> redirect * ?\nsecond line \\ ünïcödé αβγ 日本 %s %n";
    ProcessOptions options;
    options.working_directory = tmp.path().string();
    EXPECT_EQ(run_process({"/usr/bin/printf", "%s", hostile}, options).out, hostile);
    // Through env (execvp, no shell) as well, and as an environment value.
    options.env = {{"HOSTILE", hostile}};
    EXPECT_EQ(run_process({"/usr/bin/env", "printf", "%s", hostile}, options).out, hostile);
    EXPECT_NE(run_process({"/usr/bin/env"}, options).out.find("HOSTILE=" + hostile + "\n"), std::string::npos);
    EXPECT_TRUE(tmp.entries().empty()) << "a file was created: " << tmp.entries().front();
}

TEST(Process, ProgramsAreFoundOnPath) {
    const auto sh = find_program("sh");
    ASSERT_TRUE(sh);
    EXPECT_EQ(std::filesystem::path(*sh).filename(), "sh");
    EXPECT_EQ(find_program("/bin/sh"), "/bin/sh");
    EXPECT_FALSE(find_program("shatter-no-such-program-7f3a"));
    EXPECT_FALSE(find_program("/etc/passwd"));  // exists but not executable
    EXPECT_EQ(run_process({"echo", "hi"}).out, "hi\n");
}

TEST(Process, ProgramThatCannotStartIsAToolError) {
    try {
        run_process({"shatter-no-such-program-7f3a", "x"});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Tool);
        EXPECT_NE(std::string(e.what()).find("shatter-no-such-program-7f3a"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("(fix: "), std::string::npos);
    }
    ProcessOptions options;
    options.working_directory = "/no/such/directory";
    try {
        run_process({"/bin/true"}, options);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Tool);
        EXPECT_NE(std::string(e.what()).find("/no/such/directory"), std::string::npos);
    }
}

TEST(Process, ChildProcessPollsWithoutBlockingThenReportsItsEnd) {
    ChildProcess child({"/bin/sh", "-c", "sleep 0.2; echo done; exit 4"}, {});
    EXPECT_GT(child.pid(), 0);
    const auto start = std::chrono::steady_clock::now();
    EXPECT_FALSE(child.poll());
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(100));
    std::optional<ProcessResult> r;
    while (!(r = child.poll())) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_EQ(r->exit_code, 4);
    EXPECT_EQ(r->out, "done\n");
    EXPECT_EQ(child.wait().exit_code, 4);  // stays known
}

TEST(Process, ChildProcessStillRunningIsKilledAndReapedOnDestruction) {
    int pid = 0;
    const auto start = std::chrono::steady_clock::now();
    {
        ChildProcess child({"/bin/sleep", "30"}, {});
        pid = child.pid();
    }
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
    EXPECT_EQ(::kill(pid, 0), -1);  // gone, and reaped (no zombie to signal)
    EXPECT_EQ(errno, ESRCH);
}

TEST(Process, MessageHelpersQuoteAndTrim) {
    EXPECT_EQ(command_line({"ffmpeg", "-i", "it's here"}), "'ffmpeg' '-i' 'it'\\''s here'");
    EXPECT_EQ(last_lines("a\nb\n\nc\r\nd\n\n", 2), "c\nd");
    EXPECT_EQ(last_lines("only", 5), "only");
    EXPECT_EQ(last_lines("", 5), "");
}

}  // namespace
}  // namespace shatter
