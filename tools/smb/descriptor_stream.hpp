// SPDX-License-Identifier: MIT
#pragma once
// An output stream over a file descriptor that keeps the system's reason for a failed write.
// std::ofstream and std::cout set badbit and lose errno: by the time the tool says that a write
// failed, errno may hold anything, so "No space left on device" would be lost.

#include <array>
#include <ostream>
#include <streambuf>

namespace smb::io {

/// A buffer that writes to a descriptor (which it does not own). After a failed write every
/// later write fails too, and error() holds the errno of the first failure.
class DescriptorBuffer final : public std::streambuf {
public:
    explicit DescriptorBuffer(int descriptor);

    /// The errno of the first failed write, or 0.
    [[nodiscard]] int error() const noexcept { return error_; }

protected:
    int_type overflow(int_type c) override;
    std::streamsize xsputn(const char* text, std::streamsize count) override;
    int sync() override;

private:
    /// Writes what the buffer holds; false after a failure.
    bool drain();
    bool write_all(const char* text, std::size_t count);

    int descriptor_;
    int error_ = 0;
    std::array<char, std::size_t{1} << 16> buffer_{};
};

/// A descriptor, its buffer and the stream over them; close() ends the descriptor.
class DescriptorStream {
public:
    /// Takes ownership of `descriptor`.
    explicit DescriptorStream(int descriptor);
    ~DescriptorStream();
    DescriptorStream(const DescriptorStream&) = delete;
    DescriptorStream& operator=(const DescriptorStream&) = delete;

    [[nodiscard]] std::ostream& stream() noexcept { return stream_; }
    /// Flushes and closes the descriptor; returns 0, or the errno of the first failure (of a
    /// write, the flush or the close).
    int close();
    /// The errno of the first failed write, or 0.
    [[nodiscard]] int error() const noexcept { return buffer_.error(); }

private:
    int descriptor_;
    DescriptorBuffer buffer_;
    std::ostream stream_;
};

}  // namespace smb::io
