// SPDX-License-Identifier: MIT
// Where `smb pairs -o` and `smb generate -o` write: a symbolic link stays a link and its final
// target gets the content; a FIFO or a device is written into, never replaced; a regular file is
// replaced only by a complete output. Devices are private nodes in the test's folder (mknod), so
// that a faulty tool could never replace the system's /dev/null or /dev/full.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <string>
#include <thread>

#include "test_cli_support.hpp"

namespace smb::cli_test {
namespace {

const std::string scene_2d = "frame,id,xmin,ymin,xmax,ymax\n0,1,0,0,1,1\n0,2,0.5,0.5,2,2\n";
const std::string pairs_2d = "frame,a,b\n0,1,2\n";

std::vector<std::string> pairs_into(const std::string& output) { return {"pairs", "-i", "scene.csv", "-o", output}; }

bool is_link(const fs::path& path) { return fs::is_symlink(fs::symlink_status(path)); }

TEST(CliOutputTargets, SymlinkStaysALinkAndItsTargetGetsTheContent) {
    TempFolder folder;
    write_file(folder / "scene.csv", scene_2d);
    write_file(folder / "target.csv", "old\n");
    fs::create_symlink("target.csv", folder / "link.csv");
    const auto result = run_smb(folder, pairs_into("link.csv"));
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_TRUE(is_link(folder / "link.csv"));
    EXPECT_EQ(fs::read_symlink(folder / "link.csv"), "target.csv");
    EXPECT_EQ(read_file(folder / "target.csv"), pairs_2d);
    EXPECT_EQ(folder.entry_count(), 3u);  // no temporary left behind
}

TEST(CliOutputTargets, RelativeLinkInAnotherFolderIsReadFromThatFolder) {
    TempFolder folder;
    write_file(folder / "scene.csv", scene_2d);
    fs::create_directories(folder / "links");
    fs::create_directories(folder / "data");
    write_file(folder / "data" / "target.csv", "old\n");
    // Read from the working directory, "../data/target.csv" would point outside the folder.
    fs::create_symlink("../data/target.csv", folder / "links" / "out.csv");
    const auto result = run_smb(folder, pairs_into("links/out.csv"));
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_TRUE(is_link(folder / "links" / "out.csv"));
    EXPECT_EQ(read_file(folder / "data" / "target.csv"), pairs_2d);
    EXPECT_EQ(std::distance(fs::directory_iterator(folder / "links"), {}), 1);
    EXPECT_EQ(std::distance(fs::directory_iterator(folder / "data"), {}), 1);
}

TEST(CliOutputTargets, ChainOfLinksReachesTheFinalTarget) {
    TempFolder folder;
    write_file(folder / "scene.csv", scene_2d);
    fs::create_directories(folder / "deep");
    write_file(folder / "deep" / "final.csv", "old\n");
    fs::create_symlink("deep/middle.csv", folder / "first.csv");
    fs::create_symlink("final.csv", folder / "deep" / "middle.csv");
    const auto result = run_smb(folder, pairs_into("first.csv"));
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_TRUE(is_link(folder / "first.csv"));
    EXPECT_TRUE(is_link(folder / "deep" / "middle.csv"));
    EXPECT_EQ(read_file(folder / "deep" / "final.csv"), pairs_2d);
}

TEST(CliOutputTargets, DanglingLinkCreatesItsTarget) {
    TempFolder folder;
    fs::create_directories(folder / "out");
    fs::create_symlink("out/new.csv", folder / "link.csv");
    const auto result = run_smb(folder, {"generate", "--dim", "2", "-n", "5", "-s", "2", "-o", "link.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_TRUE(is_link(folder / "link.csv"));
    EXPECT_TRUE(read_file(folder / "out" / "new.csv").starts_with("frame,id,xmin,ymin,xmax,ymax\n"));
    EXPECT_EQ(std::distance(fs::directory_iterator(folder / "out"), {}), 1);
}

TEST(CliOutputTargets, LoopOfLinksIsRefused) {
    TempFolder folder;
    write_file(folder / "scene.csv", scene_2d);
    fs::create_symlink("b.csv", folder / "a.csv");
    fs::create_symlink("a.csv", folder / "b.csv");
    const auto result = run_smb(folder, pairs_into("a.csv"));
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("cannot write 'a.csv': too many symbolic links"), std::string::npos) << result.err;
    EXPECT_TRUE(is_link(folder / "a.csv"));
    EXPECT_TRUE(is_link(folder / "b.csv"));
    EXPECT_EQ(folder.entry_count(), 3u);
}

TEST(CliOutputTargets, FailedRunThroughALinkKeepsTheTarget) {
    TempFolder folder;
    write_file(folder / "scene.csv", scene_2d + "1,1,0,0,1\n");
    write_file(folder / "target.csv", "old\n");
    fs::create_symlink("target.csv", folder / "link.csv");
    const auto result = run_smb(folder, pairs_into("link.csv"));
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("scene.csv:4: "), std::string::npos) << result.err;
    EXPECT_TRUE(is_link(folder / "link.csv"));
    EXPECT_EQ(read_file(folder / "target.csv"), "old\n");
    EXPECT_EQ(folder.entry_count(), 3u);
}

TEST(CliOutputTargets, FailedGenerateKeepsThePreviousFile) {
    TempFolder folder;
    write_file(folder / "scene.csv", "previous\n");
    const auto result = run_smb(folder, {"generate", "-n", "1", "-E", "0.9", "-o", "scene.csv"});
    EXPECT_EQ(result.status, 1);
    EXPECT_EQ(read_file(folder / "scene.csv"), "previous\n");
    EXPECT_EQ(folder.entry_count(), 1u);
}

TEST(CliOutputTargets, ReplacedFileKeepsItsPermissions) {
    TempFolder folder;
    write_file(folder / "scene.csv", scene_2d);
    write_file(folder / "pairs.csv", "old\n");
    fs::permissions(folder / "pairs.csv", fs::perms::owner_read | fs::perms::owner_write);
    const auto result = run_smb(folder, pairs_into("pairs.csv"));
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(read_file(folder / "pairs.csv"), pairs_2d);
    EXPECT_EQ(fs::status(folder / "pairs.csv").permissions() & fs::perms::all,
              fs::perms::owner_read | fs::perms::owner_write);
}

/// Reads a FIFO on a thread of its own until the writer is done. The FIFO is opened without
/// blocking, so that a tool that never opens it (or replaces it) cannot hang the test.
class FifoReader {
public:
    explicit FifoReader(const fs::path& fifo) {
        descriptor_ = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
        if (descriptor_ >= 0) thread_ = std::thread([this] { read_until_done(); });
    }
    ~FifoReader() {
        if (thread_.joinable()) finish();
        if (descriptor_ >= 0) ::close(descriptor_);
    }
    FifoReader(const FifoReader&) = delete;
    FifoReader& operator=(const FifoReader&) = delete;

    [[nodiscard]] bool opened() const { return descriptor_ >= 0; }
    /// Call once the writing process has exited: what it wrote.
    std::string finish() {
        writer_done_ = true;
        thread_.join();
        return received_;
    }

private:
    void read_until_done() {
        char buffer[4096];
        for (;;) {
            const bool done = writer_done_;  // read before draining: no write can follow it
            const ssize_t count = ::read(descriptor_, buffer, sizeof buffer);
            if (count > 0) {
                received_.append(buffer, static_cast<std::size_t>(count));
            } else if (done && (count == 0 || errno != EINTR)) {
                return;
            } else {
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            }
        }
    }

    int descriptor_ = -1;
    std::atomic<bool> writer_done_{false};
    std::string received_;
    std::thread thread_;
};

TEST(CliOutputTargets, FifoIsWrittenIntoNotReplaced) {
    TempFolder folder;
    write_file(folder / "scene.csv", scene_2d);
    ASSERT_EQ(::mkfifo((folder / "pipe").c_str(), 0600), 0);
    FifoReader reader(folder / "pipe");
    ASSERT_TRUE(reader.opened());
    const auto result = run_smb(folder, pairs_into("pipe"));
    const std::string received = reader.finish();
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(received, pairs_2d);
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(folder / "pipe")));
    EXPECT_EQ(folder.entry_count(), 2u);
}

/// A character device node in `folder` with the numbers of /dev/`name` (Linux: null 1:3, full
/// 1:7), ready to be written. Where nodes cannot be made (no privilege, a nodev file system), the
/// system's own /dev/`name`, but only when this process cannot replace files in /dev (so not even
/// a faulty tool could break it); else an empty path: the test is skipped.
fs::path character_device(const TempFolder& folder, const std::string& name, unsigned minor) {
    const fs::path node = folder / name;
    if (::mknod(node.c_str(), S_IFCHR | 0666, ::makedev(1, minor)) == 0) {
        const int descriptor = ::open(node.c_str(), O_WRONLY);
        if (descriptor >= 0) {
            ::close(descriptor);
            return node;
        }
        fs::remove(node);
    }
    const fs::path system_device = fs::path("/dev") / name;
    if (::access("/dev", W_OK) != 0 && fs::is_character_file(system_device)) return system_device;
    return {};
}

TEST(CliOutputTargets, NullDeviceStaysADevice) {
    TempFolder folder;
    write_file(folder / "scene.csv", scene_2d);
    const fs::path null_device = character_device(folder, "null", 3);
    if (null_device.empty()) GTEST_SKIP() << "no character device to write safely";
    const auto pairs = run_smb(folder, pairs_into(null_device.string()));
    EXPECT_EQ(pairs.status, 0) << pairs.err;
    EXPECT_TRUE(fs::is_character_file(fs::symlink_status(null_device)));
    const auto generate = run_smb(folder, {"generate", "-n", "5", "-s", "1", "-o", null_device.string()});
    EXPECT_EQ(generate.status, 0) << generate.err;
    EXPECT_TRUE(fs::is_character_file(fs::symlink_status(null_device)));
    EXPECT_EQ(read_file(null_device), "");
}

TEST(CliOutputTargets, FullDeviceReportsTheWriteError) {
    TempFolder folder;
    write_file(folder / "scene.csv", scene_2d);
    const fs::path full_device = character_device(folder, "full", 7);
    if (full_device.empty()) GTEST_SKIP() << "no character device to write safely";
    const std::string full = ": " + std::string(std::strerror(ENOSPC));  // ": No space left on device"
    const auto pairs = run_smb(folder, pairs_into(full_device.string()));
    EXPECT_EQ(pairs.status, 1);
    EXPECT_NE(pairs.err.find("smb: error: writing failed for '" + full_device.string() + "'" + full), std::string::npos)
        << pairs.err;
    EXPECT_TRUE(fs::is_character_file(fs::symlink_status(full_device)));
    const auto generate = run_smb(folder, {"generate", "-n", "5", "-s", "1", "-o", full_device.string()});
    EXPECT_EQ(generate.status, 1);
    EXPECT_NE(generate.err.find("smb: error: writing failed for '" + full_device.string() + "'" + full),
              std::string::npos)
        << generate.err;
    EXPECT_TRUE(fs::is_character_file(fs::symlink_status(full_device)));
    // Standard output on the full device: each command that prints says why it failed.
    for (const std::vector<std::string>& arguments :
         {std::vector<std::string>{"run", "-n", "100", "-s", "2", "--json"},
          std::vector<std::string>{"run", "-n", "100", "-s", "2"}, pairs_into("-"),
          std::vector<std::string>{"generate", "-n", "5", "-s", "1"}}) {
        const auto result = run_smb_with(folder, arguments, {}, full_device);
        EXPECT_EQ(result.status, 1) << arguments[0];
        EXPECT_NE(result.err.find("smb: error: writing to standard output failed" + full), std::string::npos)
            << arguments[0] << ": " << result.err;
    }
}

/// Starts smb with `arguments` in `folder`, its standard input the returned descriptor (the
/// write end of a pipe), its output to the test's standard error.
pid_t start_smb(const TempFolder& folder, const std::vector<std::string>& arguments, int& input) {
    int ends[2];
    if (::pipe(ends) != 0) return -1;
    const pid_t child = ::fork();
    if (child == 0) {
        const rlimit no_core{0, 0};  // the signals that dump core leave no core in the folder
        ::setrlimit(RLIMIT_CORE, &no_core);
        ::signal(SIGPIPE, SIG_DFL);  // ignored by the test, which an exec would keep
        ::dup2(ends[0], STDIN_FILENO);
        ::close(ends[0]);
        ::close(ends[1]);
        if (::chdir(folder.path().c_str()) != 0) ::_exit(127);
        std::vector<char*> argv;
        std::string program = SMB_CLI_PATH;
        argv.push_back(program.data());
        std::vector<std::string> copies = arguments;
        for (auto& argument : copies) argv.push_back(argument.data());
        argv.push_back(nullptr);
        ::execv(program.c_str(), argv.data());
        ::_exit(127);
    }
    ::close(ends[0]);
    input = ends[1];
    return child;
}

/// The names in `folder` that start with `prefix`.
std::vector<std::string> names_starting(const TempFolder& folder, const std::string& prefix) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder.path())) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with(prefix)) names.push_back(name);
    }
    return names;
}

TEST(CliOutputTargets, ASignalMidOutputLeavesNoPartialFile) {
    // The first frame, longer than what the tool reads at once (1 MiB), and not finished: the
    // tool has read the header, opened its output and waits for the rest of the frame.
    std::string start = "frame,id,xmin,ymin,xmax,ymax\n";
    for (int id = 0; start.size() < (std::size_t{3} << 19); ++id)
        start += fmt::format("0,{},{},0,{}.5,1\n", id, 2 * id, 2 * id);
    const auto previous_pipe_action = ::signal(SIGPIPE, SIG_IGN);  // a tool that died early: EPIPE
    for (const int signal : {SIGTERM, SIGINT, SIGHUP, SIGSEGV, SIGABRT}) {
        TempFolder folder;
        write_file(folder / "out.csv", "the previous output\n");
        int input = -1;
        const pid_t child = start_smb(folder, {"pairs", "-i", "-", "-o", "out.csv"}, input);
        ASSERT_GT(child, 0);
        for (std::size_t written = 0; written < start.size();) {
            const ssize_t more = ::write(input, start.data() + written, start.size() - written);
            ASSERT_GT(more, 0) << std::strerror(errno);
            written += static_cast<std::size_t>(more);
        }
        bool partial = false;
        for (int wait = 0; wait < 1000 && !partial; ++wait) {
            partial = !names_starting(folder, ".out.csv.smb-partial-").empty();
            if (!partial) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        EXPECT_TRUE(partial) << "signal " << signal << ": no partial file appeared";
        ::kill(child, signal);
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        ::close(input);
        // The signal ends the program as it would have without the clean-up; under a sanitizer,
        // whose handler reports a SIGSEGV, with a failure status, or by SIGABRT where the
        // sanitizer is told to abort on errors (abort_on_error=1, as CI runs it).
        const bool by_signal = WIFSIGNALED(status) && WTERMSIG(status) == signal;
        const bool by_sanitizer = signal == SIGSEGV && ((WIFEXITED(status) && WEXITSTATUS(status) != 0) ||
                                                        (WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT));
        EXPECT_TRUE(by_signal || by_sanitizer) << "signal " << signal << ", status " << status;
        EXPECT_TRUE(names_starting(folder, ".out.csv").empty()) << "signal " << signal;
        EXPECT_EQ(read_file(folder / "out.csv"), "the previous output\n") << "signal " << signal;
        EXPECT_EQ(folder.entry_count(), 1u) << "signal " << signal;
    }
    ::signal(SIGPIPE, previous_pipe_action);
}

TEST(CliOutputTargets, FolderIsRefusedByName) {
    TempFolder folder;
    write_file(folder / "scene.csv", scene_2d);
    fs::create_directories(folder / "out");
    const auto result = run_smb(folder, pairs_into("out"));
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("'out': it is a folder"), std::string::npos) << result.err;
}

}  // namespace
}  // namespace smb::cli_test
