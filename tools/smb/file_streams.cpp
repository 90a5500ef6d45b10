// SPDX-License-Identifier: MIT
#include "file_streams.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <vector>

namespace smb::io {

namespace {

/// "<what> '<path>'", with the system's reason when errno holds one.
std::runtime_error system_error(const std::string& what, const std::string& path) {
    std::string message = what + " '" + path + "'";
    if (errno != 0) {
        message += ": ";
        message += std::strerror(errno);
    }
    return std::runtime_error(message);
}

/// The permissions a plain open() would give a new file: 0666 less the umask.
mode_t default_file_mode() {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    return static_cast<mode_t>(0666 & ~mask);
}

/// What a write to `path` reaches: its symlinks followed to the final target, each relative link
/// read from the folder the link lies in. A dangling link gives the path it points to, which the
/// output then creates.
std::string final_target(const std::string& path) {
    constexpr int most_links = 40;  // as the kernel's own limit (ELOOP)
    std::filesystem::path current(path);
    for (int links = 0;; ++links) {
        struct stat status {};
        if (::lstat(current.c_str(), &status) != 0 || !S_ISLNK(status.st_mode)) return current.string();
        if (links == most_links) throw std::runtime_error("cannot write '" + path + "': too many symbolic links");
        std::error_code error;
        const std::filesystem::path link = std::filesystem::read_symlink(current, error);
        if (error)
            throw std::runtime_error("cannot read the symbolic link '" + current.string() + "': " + error.message());
        current = link.is_absolute() ? link : current.parent_path() / link;
    }
}

}  // namespace

InputFile::InputFile(const std::string& path) {
    if (path == "-") {
        stream_ = &std::cin;
        name_ = "<stdin>";
        return;
    }
    std::error_code ignored;
    if (std::filesystem::is_directory(path, ignored))
        throw std::runtime_error("cannot read '" + path + "': it is a folder");
    errno = 0;
    file_ = std::make_unique<std::ifstream>(path, std::ios::binary);
    if (!*file_) throw system_error("cannot open", path);
    stream_ = file_.get();
    name_ = path;
}

OutputFile::OutputFile(const std::string& path) : path_(path) {
    if (path == "-") {
        stream_ = &std::cout;
        return;
    }
    target_ = final_target(path);
    struct stat status {};
    const bool exists = ::stat(target_.c_str(), &status) == 0;
    if (exists && S_ISDIR(status.st_mode)) throw std::runtime_error("cannot write '" + path + "': it is a folder");
    if (exists && !S_ISREG(status.st_mode)) {
        // A FIFO or a device cannot be replaced by a file without breaking whoever uses it (a
        // reader at the other end, /dev/null for every other program): write into it.
        errno = 0;
        file_ = std::make_unique<std::ofstream>(target_, std::ios::binary);
        if (!*file_) throw system_error("cannot open", path);
        stream_ = file_.get();
        return;
    }
    // The temporary lives beside the target so that the final rename stays on one file system
    // and is atomic.
    const std::filesystem::path target(target_);
    const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
    std::string hidden_name = ".";  // appended piecewise: GCC 12 misreads "." + string (-Wrestrict)
    hidden_name += target.filename().string();
    hidden_name += ".tmp-XXXXXX";
    const std::string pattern = (folder / hidden_name).string();
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    const int descriptor = ::mkstemp(name.data());
    if (descriptor < 0) throw system_error("cannot create a file in the folder of", path);
    // A file that is replaced keeps its permissions (not set-id bits: it is data); a new one gets
    // what open() would give it.
    ::fchmod(descriptor, exists ? static_cast<mode_t>(status.st_mode & 0777) : default_file_mode());
    ::close(descriptor);
    temporary_path_ = name.data();
    file_ = std::make_unique<std::ofstream>(temporary_path_, std::ios::binary | std::ios::trunc);
    if (!*file_) {
        std::remove(temporary_path_.c_str());
        throw system_error("cannot write", path);
    }
    stream_ = file_.get();
}

OutputFile::~OutputFile() {
    if (file_ && !committed_) {
        file_->close();
        if (!temporary_path_.empty()) std::remove(temporary_path_.c_str());
    }
}

void OutputFile::commit() {
    if (!file_) {
        flush_standard_output();
        committed_ = true;
        return;
    }
    errno = 0;
    file_->close();
    if (!*file_) throw system_error("writing failed for", path_);
    if (!temporary_path_.empty() && std::rename(temporary_path_.c_str(), target_.c_str()) != 0)
        throw system_error("cannot move the output into place at", path_);
    committed_ = true;
}

void OutputFile::throw_if_failed() const {
    if (*stream_) return;
    std::string message =
        file_ ? "writing failed for '" + path_ + "'" : std::string("writing to standard output failed");
    if (errno != 0) {
        message += ": ";
        message += std::strerror(errno);
    }
    throw std::runtime_error(message);
}

void flush_standard_output() {
    errno = 0;
    std::cout.flush();
    if (!std::cout) {
        std::string message = "writing to standard output failed";
        if (errno != 0) {
            message += ": ";
            message += std::strerror(errno);
        }
        throw std::runtime_error(message);
    }
}

void close_standard_output() {
    flush_standard_output();
    errno = 0;
    // EBADF: standard output was closed before the program started and nothing was written.
    if (::close(STDOUT_FILENO) != 0 && errno != EBADF)
        throw std::runtime_error(std::string("closing standard output failed: ") + std::strerror(errno));
}

}  // namespace smb::io
