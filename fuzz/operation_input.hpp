// SPDX-License-Identifier: MIT
#pragma once
// What the operation fuzzers (world_ops_check.hpp, detector_ops_check.hpp) share: reading the
// input's bytes as ids and coordinates (a small grid, hostile values, raw bytes), and checking
// one detection against brute force.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "smb/box.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"
#include "smb/settings.hpp"

namespace smb::fuzz::world_ops_detail {

/// The most boxes a model holds, so that one input runs in well under a millisecond.
constexpr std::size_t kMaxBoxes = 64;
/// Ids come from a small range, so that inserts collide and removes find their boxes.
constexpr std::uint8_t kIdRange = 80;

[[noreturn]] inline void broken_promise(const char* what) {
    throw std::logic_error(std::string("world operations: ") + what);
}

/// Reads the fuzz input front to back; past the end every read gives zero.
class ByteReader {
public:
    ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

    [[nodiscard]] bool done() const { return position_ >= size_; }

    std::uint8_t byte() { return position_ < size_ ? data_[position_++] : 0; }

    template <typename T>
    T raw() {
        unsigned char bytes[sizeof(T)] = {};
        for (auto& b : bytes) b = byte();
        T value;
        std::memcpy(&value, bytes, sizeof(T));
        return value;
    }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t position_ = 0;
};

template <typename Real>
Real hostile_value(std::uint8_t index) {
    using limits = std::numeric_limits<Real>;
    const Real table[] = {
        Real(0),
        -Real(0),
        Real(1),
        Real(-1),
        Real(0.5),
        limits::denorm_min(),
        -limits::denorm_min(),
        limits::min(),
        limits::epsilon(),
        Real(1) + limits::epsilon(),
        limits::max(),
        limits::lowest(),
        limits::max() / Real(2),
        limits::infinity(),
        -limits::infinity(),
        limits::quiet_NaN(),
        Real(1e30),
        Real(-1e30),
        Real(16777216),  // 2^24: the float spacing is 2 beyond it
        Real(9007199254740992.0),
    };
    constexpr std::size_t count = sizeof(table) / sizeof(table[0]);
    return table[index % count];
}

/// One coordinate: mostly a small grid (touching boxes), sometimes hostile, sometimes raw.
template <typename Real>
Real decode_coordinate(ByteReader& in) {
    const std::uint8_t selector = in.byte();
    if (selector < 160) return static_cast<Real>(static_cast<int>(selector % 16) - 4) / Real(2);
    if (selector < 240) return hostile_value<Real>(in.byte());
    return in.raw<Real>();
}

template <typename Real, int Dim>
smb::Box<Real, Dim> decode_box(ByteReader& in) {
    smb::Box<Real, Dim> box;
    for (int k = 0; k < Dim; ++k) {
        box.min[k] = decode_coordinate<Real>(in);
        // Mostly a valid extent above min, so that most boxes are accepted.
        const std::uint8_t shape = in.byte();
        if (shape < 200) {
            box.max[k] = box.min[k] + static_cast<Real>(shape % 8) / Real(2);
        } else {
            box.max[k] = decode_coordinate<Real>(in);
        }
    }
    return box;
}

inline smb::BoxId decode_id(ByteReader& in) {
    const std::uint8_t value = in.byte();
    if (value == 255) return std::numeric_limits<smb::BoxId>::max();
    if (value == 254) return std::numeric_limits<smb::BoxId>::max() - 1;
    return value % kIdRange;
}

/// One detection, into a vector or through a sink (`detect` is called with either), checked
/// against `expected` (brute force, sorted): chunk sizes, the pair limit, a < b, the pairs.
template <typename Detect>
void check_detection(const std::vector<smb::Pair>& expected, const smb::DetectionSettings& settings, bool through_sink,
                     Detect detect) {
    std::vector<smb::Pair> found;
    bool over_limit = false;
    if (through_sink) {
        smb::PairSink sink = [&](std::span<const smb::Pair> chunk) {
            if (chunk.empty() || chunk.size() > settings.pair_chunk_size) broken_promise("a chunk of a wrong size");
            found.insert(found.end(), chunk.begin(), chunk.end());
        };
        detect(sink);
    } else {
        try {
            detect(found);
        } catch (const smb::PairLimitError&) {
            over_limit = true;
        }
    }
    const bool should_be_over = !through_sink && expected.size() > settings.max_pairs_held;
    if (over_limit != should_be_over) broken_promise("the pair limit was not kept");
    if (over_limit) return;
    for (const smb::Pair& pair : found)
        if (!(pair.a < pair.b)) broken_promise("a pair with a >= b");
    smb::sort_pairs(found);
    if (found != expected) broken_promise("the pairs differ from brute force");
}

}  // namespace smb::fuzz::world_ops_detail
