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

std::runtime_error system_error(const std::string& what, const std::string& path) {
    return std::runtime_error(what + " '" + path + "': " + std::strerror(errno));
}

/// The permissions a plain open() would give a new file: 0666 less the umask.
mode_t default_file_mode() {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    return static_cast<mode_t>(0666 & ~mask);
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
    // The temporary lives beside the target so that the final rename stays on one file system
    // and is atomic.
    const std::filesystem::path target(path);
    const std::filesystem::path folder =
        target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
    std::string hidden_name = ".";  // appended piecewise: GCC 12 misreads "." + string (-Wrestrict)
    hidden_name += target.filename().string();
    hidden_name += ".tmp-XXXXXX";
    const std::string pattern = (folder / hidden_name).string();
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    const int descriptor = ::mkstemp(name.data());
    if (descriptor < 0) throw system_error("cannot create a file in the folder of", path);
    ::fchmod(descriptor, default_file_mode());
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
        std::remove(temporary_path_.c_str());
    }
}

void OutputFile::commit() {
    stream_->flush();
    if (!file_) {
        if (!*stream_) throw std::runtime_error("writing to standard output failed");
        committed_ = true;
        return;
    }
    file_->close();
    if (!*file_) throw system_error("writing failed for", path_);
    if (std::rename(temporary_path_.c_str(), path_.c_str()) != 0)
        throw system_error("cannot move the output into place at", path_);
    committed_ = true;
}

}  // namespace smb::io
