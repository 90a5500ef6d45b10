// SPDX-License-Identifier: MIT
// Where `smb pairs -o` and `smb generate -o` write: a symbolic link stays a link and its final
// target gets the content; a FIFO or a device is written into, never replaced; a regular file is
// replaced only by a complete output. Devices are private nodes in the test's folder (mknod), so
// that a faulty tool could never replace the system's /dev/null or /dev/full.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
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
    const auto pairs = run_smb(folder, pairs_into(full_device.string()));
    EXPECT_EQ(pairs.status, 1);
    EXPECT_NE(pairs.err.find("smb: error: writing failed for '" + full_device.string() + "'"), std::string::npos)
        << pairs.err;
    EXPECT_TRUE(fs::is_character_file(fs::symlink_status(full_device)));
    const auto generate = run_smb(folder, {"generate", "-n", "5", "-s", "1", "-o", full_device.string()});
    EXPECT_EQ(generate.status, 1);
    EXPECT_NE(generate.err.find("smb: error: "), std::string::npos) << generate.err;
    EXPECT_TRUE(fs::is_character_file(fs::symlink_status(full_device)));
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
