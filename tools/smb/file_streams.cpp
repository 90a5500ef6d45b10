// SPDX-License-Identifier: MIT
#include "file_streams.hpp"

#include <fcntl.h>
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

#include "descriptor_stream.hpp"
#include "partial_files.hpp"

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

namespace {

/// std::cout's buffer once keep_standard_output_errors() was called, else null.
DescriptorBuffer* standard_output_buffer = nullptr;

/// The errno of the first failed write to standard output, where it was kept, else errno.
int standard_output_error() { return standard_output_buffer ? standard_output_buffer->error() : errno; }

std::string with_reason(std::string message, int error) {
    if (error != 0) {
        message += ": ";
        message += std::strerror(error);
    }
    return message;
}

}  // namespace

void keep_standard_output_errors() {
    if (standard_output_buffer != nullptr) return;
    // Never destroyed: std::cout is flushed after every static object is gone.
    standard_output_buffer = new DescriptorBuffer(STDOUT_FILENO);
    std::cout.flush();
    std::cout.rdbuf(standard_output_buffer);
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
        const int descriptor = ::open(target_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
        if (descriptor < 0) throw system_error("cannot open", path);
        file_ = std::make_unique<DescriptorStream>(descriptor);
        stream_ = &file_->stream();
        return;
    }
    // The temporary lives beside the target so that the final rename stays on one file system
    // and is atomic; its name says what it is to whoever finds one (after a SIGKILL).
    const std::filesystem::path target(target_);
    const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
    std::string hidden_name = ".";  // appended piecewise: GCC 12 misreads "." + string (-Wrestrict)
    hidden_name += target.filename().string();
    hidden_name += ".smb-partial-XXXXXX";
    const std::string pattern = (folder / hidden_name).string();
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    errno = 0;
    const int descriptor = ::mkostemp(name.data(), O_CLOEXEC);
    if (descriptor < 0) throw system_error("cannot create a file in the folder of", path);
    temporary_path_ = name.data();
    cleanup_slot_ = remember_partial_file(temporary_path_);
    file_ = std::make_unique<DescriptorStream>(descriptor);
    stream_ = &file_->stream();
    // A file that is replaced keeps its permissions (not set-id bits: it is data); a new one gets
    // what open() would give it.
    ::fchmod(descriptor, exists ? static_cast<mode_t>(status.st_mode & 0777) : default_file_mode());
}

OutputFile::~OutputFile() {
    if (file_ && !committed_) {
        file_->close();
        if (!temporary_path_.empty()) std::remove(temporary_path_.c_str());
    }
    forget_partial_file(cleanup_slot_);
}

void OutputFile::commit() {
    if (!file_) {
        flush_standard_output();
        committed_ = true;
        return;
    }
    if (const int error = file_->close(); error != 0)
        throw std::runtime_error(with_reason("writing failed for '" + path_ + "'", error));
    errno = 0;
    if (!temporary_path_.empty() && std::rename(temporary_path_.c_str(), target_.c_str()) != 0)
        throw system_error("cannot move the output into place at", path_);
    committed_ = true;
    forget_partial_file(cleanup_slot_);
    cleanup_slot_ = -1;
}

void OutputFile::throw_if_failed() const {
    if (*stream_) return;
    if (file_) throw std::runtime_error(with_reason("writing failed for '" + path_ + "'", file_->error()));
    throw std::runtime_error(with_reason("writing to standard output failed", standard_output_error()));
}

void flush_standard_output() {
    errno = 0;
    std::cout.flush();
    if (!std::cout) throw std::runtime_error(with_reason("writing to standard output failed", standard_output_error()));
}

void close_standard_output() {
    flush_standard_output();
    errno = 0;
    // EBADF: standard output was closed before the program started and nothing was written.
    if (::close(STDOUT_FILENO) != 0 && errno != EBADF)
        throw std::runtime_error(std::string("closing standard output failed: ") + std::strerror(errno));
}

}  // namespace smb::io
