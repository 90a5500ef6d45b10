// SPDX-License-Identifier: MIT
#include "line_reader.hpp"

#include <cstring>
#include <stdexcept>

namespace smb::io {

LineReader::LineReader(std::istream& in, std::size_t chunk_size)
    : in_(in), chunk_size_(chunk_size), buffer_(chunk_size) {}

std::optional<std::string_view> LineReader::next() {
    std::size_t searched = begin_;
    for (;;) {
        const void* newline = std::memchr(buffer_.data() + searched, '\n', end_ - searched);
        if (newline != nullptr) {
            const auto stop = static_cast<std::size_t>(static_cast<const char*>(newline) - buffer_.data());
            std::string_view line(buffer_.data() + begin_, stop - begin_);
            begin_ = stop + 1;
            ++line_number_;
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            return line;
        }
        searched = end_;
        const std::size_t consumed = begin_;
        if (!refill()) {
            if (begin_ == end_) return std::nullopt;
            std::string_view line(buffer_.data() + begin_, end_ - begin_);
            begin_ = end_;
            ++line_number_;
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            return line;
        }
        searched -= consumed;  // refill() moved the unread bytes to the front
    }
}

bool LineReader::refill() {
    if (input_done_) return false;
    if (begin_ > 0) {
        std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
        end_ -= begin_;
        begin_ = 0;
    }
    if (buffer_.size() - end_ < chunk_size_ / 2) buffer_.resize(buffer_.size() + chunk_size_);
    in_.read(buffer_.data() + end_, static_cast<std::streamsize>(buffer_.size() - end_));
    const auto got = static_cast<std::size_t>(in_.gcount());
    end_ += got;
    if (in_.bad()) throw std::runtime_error("read error");
    if (!in_) input_done_ = true;
    return got > 0 || !input_done_;
}

}  // namespace smb::io
