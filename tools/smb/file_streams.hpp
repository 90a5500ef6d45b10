// SPDX-License-Identifier: MIT
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

class DescriptorStream;

/// Writes to standard output for "-", otherwise to what `path` names, symlinks followed to their
/// final target (a relative link read from the link's folder; the target of a dangling link is
/// created), so that a link stays a link and its target gets the content.
///  - A regular file, or nothing yet: the output goes to a temporary file in the target's folder,
///    named .<name>.smb-partial-XXXXXX, renamed onto the target by commit(). An output that
///    failed half way is removed by the destructor, and by the handler of any signal that ends
///    the program (partial_files.hpp; SIGKILL cannot be caught), so a file at the target is
///    always complete (or the previous one, untouched).
///  - Anything else that exists (a FIFO, a character device such as /dev/null): written straight
///    through, never replaced.
/// A failed write keeps the system's reason (errno) for the message.
class OutputFile {
public:
    explicit OutputFile(const std::string& path);
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    [[nodiscard]] std::ostream& stream() noexcept { return *stream_; }
    [[nodiscard]] bool is_standard_output() const noexcept { return file_ == nullptr; }

    /// Flushes and, for a regular file, moves it into place. Throws std::runtime_error on failure.
    void commit();
    /// Throws std::runtime_error naming the destination (and the system's reason) if a write to
    /// stream() failed; call it where a writer gave up, so that the message says where.
    void throw_if_failed() const;

private:
    std::string path_;            ///< as the user gave it, for messages
    std::string target_;          ///< `path_` with its symlinks followed
    std::string temporary_path_;  ///< empty when written straight through
    std::unique_ptr<DescriptorStream> file_;
    std::ostream* stream_;
    int cleanup_slot_ = -1;  ///< where the signal handlers find temporary_path_, or -1
    bool committed_ = false;
};

/// Sends std::cout through a buffer that keeps the system's reason for a failed write, so that
/// the messages of flush_standard_output() and OutputFile say it. Call first thing in main().
void keep_standard_output_errors();

/// Flushes standard output; throws std::runtime_error when what was written could not be (a full
/// disk, a closed pipe, /dev/full), so that the exit status can say so.
void flush_standard_output();

/// Flushes and closes standard output, for the end of the program: a file system may report a
/// failed write only when the file is closed. Throws std::runtime_error as flush_standard_output.
void close_standard_output();

}  // namespace smb::io
