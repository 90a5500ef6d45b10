// SPDX-License-Identifier: MIT
#include "event_csv.hpp"

#include <fmt/format.h>

#include <cstddef>
#include <iterator>
#include <stdexcept>
#include <string_view>

#include "csv_fields.hpp"

namespace smb::io {

namespace {

constexpr std::string_view event_header = "frame,a,b,event";

}  // namespace

EventWriter::EventWriter(std::ostream& out) : out_(out) {
    buffer_.append(event_header);
    buffer_ += '\n';
}

EventWriter::~EventWriter() {
    try {
        flush();
    } catch (...) {
        // A destructor must not throw; callers who care about errors call flush() themselves.
    }
}

void EventWriter::write_frame(std::uint64_t frame, std::span<const Pair> begun, std::span<const Pair> ended) {
    auto out = std::back_inserter(buffer_);
    std::size_t b = 0;
    std::size_t e = 0;
    // A merge of the two sorted lists: the rows come out in (a, b, event) order, "begin" < "end".
    while (b < begun.size() || e < ended.size()) {
        if (e == ended.size() || (b < begun.size() && !(ended[e] < begun[b]))) {
            fmt::format_to(out, "{},{},{},begin\n", frame, begun[b].a, begun[b].b);
            ++b;
        } else {
            fmt::format_to(out, "{},{},{},end\n", frame, ended[e].a, ended[e].b);
            ++e;
        }
        if (buffer_.size() >= csv_flush_threshold) flush();
    }
}

void EventWriter::flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
    if (!out_) throw std::runtime_error("writing the events failed");
}

}  // namespace smb::io
