// SPDX-License-Identifier: MIT
#pragma once
// The scene CSV reader of the smb tool on arbitrary bytes: the check behind the fuzz_scene_csv
// target and behind the replay of its inputs in the tests.
//
// The reader may only ever return frames or throw io::CsvError. Every frame it returns must
// obey the format's promises (ids strictly increasing, valid boxes, increasing frame numbers),
// and writing the frames back out and reading them again must give the same frames.

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "csv_error.hpp"
#include "scene_csv.hpp"

namespace smb::fuzz {

namespace scene_csv_detail {

[[noreturn]] inline void broken_promise(const char* what) { throw std::logic_error(std::string("scene CSV: ") + what); }

template <int Dim>
std::vector<smb::io::SceneFrame<Dim>> read_frames(smb::io::SceneReader& reader) {
    std::vector<smb::io::SceneFrame<Dim>> frames;
    smb::io::SceneFrame<Dim> frame;
    while (reader.read_frame(frame)) {
        if (!frames.empty() && frame.number <= frames.back().number) broken_promise("frame numbers do not increase");
        if (frame.ids.size() != frame.boxes.size()) broken_promise("ids and boxes differ in length");
        for (std::size_t i = 0; i < frame.ids.size(); ++i) {
            if (i > 0 && frame.ids[i - 1] >= frame.ids[i]) broken_promise("ids not increasing");
            if (!smb::is_valid(frame.boxes[i])) broken_promise("invalid box accepted");
        }
        frames.push_back(frame);
    }
    return frames;
}

template <int Dim>
void check_round_trip(const std::vector<smb::io::SceneFrame<Dim>>& frames) {
    std::ostringstream out;
    {
        smb::io::SceneWriter writer(out, Dim);
        for (const auto& frame : frames) writer.write_frame<Dim>(frame.number, frame.ids, frame.boxes);
        writer.flush();
    }
    std::istringstream in(out.str());
    smb::io::SceneReader again(in, "round trip");
    const auto reread = read_frames<Dim>(again);
    if (reread.size() != frames.size()) broken_promise("round trip changed the frame count");
    for (std::size_t f = 0; f < frames.size(); ++f) {
        if (reread[f].number != frames[f].number || reread[f].ids != frames[f].ids ||
            reread[f].boxes != frames[f].boxes)
            broken_promise("round trip changed a frame");
    }
}

template <int Dim>
void read_and_check(smb::io::SceneReader& reader) {
    const auto frames = read_frames<Dim>(reader);
    check_round_trip<Dim>(frames);
}

}  // namespace scene_csv_detail

/// Reads `data` as a scene CSV; throws std::logic_error at the first broken promise, anything
/// else the reader throws but io::CsvError propagates too.
inline void check_scene_csv(const std::uint8_t* data, std::size_t size) {
    using namespace scene_csv_detail;
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    try {
        smb::io::SceneReader reader(in, "fuzz input");
        if (reader.dimension() == 2) {
            read_and_check<2>(reader);
        } else {
            read_and_check<3>(reader);
        }
    } catch (const smb::io::CsvError&) {
        // The one way the reader is allowed to refuse its input.
    }
}

}  // namespace smb::fuzz
