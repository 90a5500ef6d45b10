#pragma once
// Where the tool reads and writes: a path, or "-" for the standard streams.

#include <fstream>
#include <istream>
#include <memory>
#include <ostream>
#include <string>

namespace smb::io {

/// Opens `path` for reading, or standard input for "-". Throws std::runtime_error naming the
/// path when it cannot be opened.
class InputFile {
public:
    explicit InputFile(const std::string& path);

    [[nodiscard]] std::istream& stream() noexcept { return *stream_; }
    /// The name for messages: the path, or "<stdin>".
    [[nodiscard]] const std::string& name() const noexcept { return name_; }

private:
    std::unique_ptr<std::ifstream> file_;
    std::istream* stream_;
    std::string name_;
};

/// Writes to standard output for "-"; otherwise to a temporary file in the folder of `path`,
/// renamed onto `path` by commit(). An output that failed half way is removed by the destructor,
/// so a file at `path` is always complete (or the previous one, untouched).
class OutputFile {
public:
    explicit OutputFile(const std::string& path);
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    [[nodiscard]] std::ostream& stream() noexcept { return *stream_; }
    [[nodiscard]] bool is_standard_output() const noexcept { return file_ == nullptr; }

    /// Flushes and, for a file, moves it into place. Throws std::runtime_error on failure.
    void commit();

private:
    std::string path_;
    std::string temporary_path_;
    std::unique_ptr<std::ofstream> file_;
    std::ostream* stream_;
    bool committed_ = false;
};

}  // namespace smb::io
