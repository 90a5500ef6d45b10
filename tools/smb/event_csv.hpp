// SPDX-License-Identifier: MIT
#pragma once
// The event CSV of the smb conventions (`smb pairs --events`): header `frame,a,b,event`,
// `event` being `begin` or `end`, rows sorted by (frame, a, b, event).

#include <cstdint>
#include <ostream>
#include <span>
#include <string>

#include "smb/pair.hpp"

namespace smb::io {

/// Writes the event CSV, buffering the text in large blocks.
class EventWriter {
public:
    explicit EventWriter(std::ostream& out);
    ~EventWriter();
    EventWriter(const EventWriter&) = delete;
    EventWriter& operator=(const EventWriter&) = delete;

    /// Writes the events of one frame: `begun` and `ended` each sorted by (a, b) (as
    /// PairEvents gives them), frames increasing. A pair in both writes `begin` first.
    void write_frame(std::uint64_t frame, std::span<const Pair> begun, std::span<const Pair> ended);
    /// Hands everything buffered to the stream; throws std::runtime_error if the stream failed.
    void flush();

private:
    std::ostream& out_;
    std::string buffer_;
};

}  // namespace smb::io
