// SPDX-License-Identifier: MIT
#include "descriptor_stream.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace smb::io {

DescriptorBuffer::DescriptorBuffer(int descriptor) : descriptor_(descriptor) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
}

DescriptorBuffer::int_type DescriptorBuffer::overflow(int_type c) {
    if (!drain()) return traits_type::eof();
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
    return c;
}

std::streamsize DescriptorBuffer::xsputn(const char* text, std::streamsize count) {
    if (error_ != 0) return 0;
    const auto size = static_cast<std::size_t>(count);
    const auto room = static_cast<std::size_t>(epptr() - pptr());
    if (size <= room) {
        std::memcpy(pptr(), text, size);
        pbump(static_cast<int>(size));
        return count;
    }
    // Larger than the room left: what is buffered goes first, then a large write goes straight
    // through and a small one is buffered.
    if (!drain()) return 0;
    if (size >= buffer_.size()) return write_all(text, size) ? count : 0;
    std::memcpy(pptr(), text, size);
    pbump(static_cast<int>(size));
    return count;
}

int DescriptorBuffer::sync() { return drain() ? 0 : -1; }

bool DescriptorBuffer::drain() {
    const auto size = static_cast<std::size_t>(pptr() - pbase());
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    if (error_ != 0) return false;
    return write_all(buffer_.data(), size);
}

bool DescriptorBuffer::write_all(const char* text, std::size_t count) {
    while (count > 0) {
        const ssize_t written = ::write(descriptor_, text, count);
        if (written < 0) {
            if (errno == EINTR) continue;
            error_ = errno;
            return false;
        }
        text += written;
        count -= static_cast<std::size_t>(written);
    }
    return true;
}

DescriptorStream::DescriptorStream(int descriptor) : descriptor_(descriptor), buffer_(descriptor), stream_(&buffer_) {}

DescriptorStream::~DescriptorStream() {
    if (descriptor_ >= 0) ::close(descriptor_);
}

int DescriptorStream::close() {
    stream_.flush();
    int error = buffer_.error();
    if (descriptor_ >= 0) {
        // A file system may report a failed write only when the file is closed.
        if (::close(descriptor_) != 0 && error == 0) error = errno;
        descriptor_ = -1;
    }
    return error;
}

}  // namespace smb::io
