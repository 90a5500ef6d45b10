#pragma once
// Sequences of changes to an array of boxes, each followed by a Detector call, on arbitrary
// coordinates (the hostile table and raw bytes of world_ops_check.hpp): the check behind the
// fuzz_detector_ops target and behind the replay of its inputs in the tests.
//
// The array holds only valid boxes; an invalid one is offered in a copy of the array, which the
// detector must refuse naming its index, and must then still give the array's exact pairs.
// Every detection must equal brute force, whatever the detector holds (floats or doubles).

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "smb/detector.hpp"
#include "smb/errors.hpp"
#include "world_ops_check.hpp"

namespace smb::fuzz {

namespace detector_ops_detail {

using world_ops_detail::broken_promise;
using world_ops_detail::ByteReader;
using world_ops_detail::decode_box;
using world_ops_detail::decode_coordinate;
using world_ops_detail::kMaxBoxes;

template <typename Real, int Dim>
class DetectorHarness {
public:
    using BoxT = smb::Box<Real, Dim>;

    explicit DetectorHarness(const smb::WorldSettings& settings) : detector_(settings) {}

    void run(ByteReader& in) {
        while (!in.done()) step(in);
        detect_and_compare(false);
    }

private:
    void step(ByteReader& in) {
        switch (in.byte() % 7) {
            case 0:
            case 1: append(in); break;
            case 2: replace(in); break;
            case 3: swap_remove(in); break;
            case 4: shift_all(in); break;
            case 5: detect_and_compare(in.byte() % 2 == 1); break;
            case 6:
                if (in.byte() % 8 == 0) detector_.clear();
                break;
        }
    }

    void append(ByteReader& in) {
        const BoxT box = decode_box<Real, Dim>(in);
        if (!smb::is_valid(box)) {
            offer_invalid(boxes_.size(), box);
            return;
        }
        if (boxes_.size() < kMaxBoxes) boxes_.push_back(box);
    }

    void replace(ByteReader& in) {
        if (boxes_.empty()) return;
        const std::size_t index = in.byte() % boxes_.size();
        const BoxT box = decode_box<Real, Dim>(in);
        if (smb::is_valid(box)) boxes_[index] = box;
        else offer_invalid(index, box);
    }

    void swap_remove(ByteReader& in) {
        if (boxes_.empty()) return;
        const std::size_t index = in.byte() % boxes_.size();
        boxes_[index] = boxes_.back();
        boxes_.pop_back();
    }

    /// Every box moved by one decoded offset per axis (a scene drifting far, or jumping), where
    /// that keeps it valid.
    void shift_all(ByteReader& in) {
        std::array<Real, Dim> offset{};
        for (int k = 0; k < Dim; ++k) offset[k] = decode_coordinate<Real>(in);
        for (BoxT& box : boxes_) {
            BoxT moved = box;
            for (int k = 0; k < Dim; ++k) {
                moved.min[k] += offset[k];
                moved.max[k] += offset[k];
            }
            if (smb::is_valid(moved)) box = moved;
        }
    }

    /// The array with `bad` at `index` (appended when index is the size) must be refused with
    /// an InvalidBoxError naming the index, and change nothing.
    void offer_invalid(std::size_t index, const BoxT& bad) {
        std::vector<BoxT> offered = boxes_;
        if (index == offered.size()) offered.push_back(bad);
        else offered[index] = bad;
        std::vector<smb::Pair> pairs;
        try {
            detector_.detect(offered, pairs);
        } catch (const smb::InvalidBoxError& error) {
            if (std::string(error.what()).find("box " + std::to_string(index)) == std::string::npos)
                broken_promise("an invalid box was refused under a wrong index");
            detect_and_compare(false);
            return;
        }
        broken_promise("an invalid box was accepted");
    }

    void detect_and_compare(bool through_sink) {
        std::vector<smb::Pair> expected;
        for (std::size_t a = 0; a < boxes_.size(); ++a)
            for (std::size_t b = a + 1; b < boxes_.size(); ++b)
                if (smb::overlaps(boxes_[a], boxes_[b])) expected.push_back({a, b});

        std::vector<smb::Pair> found;
        bool over_limit = false;
        if (through_sink) {
            detector_.detect(boxes_, [&](std::span<const smb::Pair> chunk) {
                if (chunk.empty() || chunk.size() > detector_.settings().pair_chunk_size)
                    broken_promise("a chunk of a wrong size");
                found.insert(found.end(), chunk.begin(), chunk.end());
            });
        } else {
            try {
                detector_.detect(boxes_, found);
            } catch (const smb::PairLimitError&) {
                over_limit = true;
            }
        }
        const bool should_be_over = !through_sink && expected.size() > detector_.settings().max_pairs_held;
        if (over_limit != should_be_over) broken_promise("the pair limit was not kept");
        if (over_limit) return;
        for (const smb::Pair& pair : found)
            if (!(pair.a < pair.b)) broken_promise("a pair with a >= b");
        smb::sort_pairs(found);
        if (found != expected) broken_promise("the detector's pairs differ from brute force");
    }

    smb::Detector<Real, Dim> detector_;
    std::vector<BoxT> boxes_;
};

template <typename Real, int Dim>
void run_detector(ByteReader& in, const smb::WorldSettings& settings) {
    DetectorHarness<Real, Dim> harness(settings);
    harness.run(in);
}

}  // namespace detector_ops_detail

/// Decodes `data` into a detector type, settings and changes to its array, and checks every
/// detection; throws std::logic_error at the first broken promise of smb.
inline void check_detector_operations(const std::uint8_t* data, std::size_t size) {
    using namespace detector_ops_detail;
    ByteReader in(data, size);
    const std::uint8_t kind = in.byte();
    smb::WorldSettings settings;
    settings.target_cell_population = 1 + in.byte() % 32;
    settings.pair_chunk_size = 1 + in.byte() % 8;
    // One thread: OpenMP's idle threads spin between inputs and slow the fuzzer tenfold; the
    // thread counts are checked against brute force by tests/test_detector.cpp.
    const std::uint8_t limit = in.byte();
    if (limit < 64) settings.max_pairs_held = limit;
    switch (kind % 4) {
        case 0: run_detector<float, 2>(in, settings); break;
        case 1: run_detector<double, 2>(in, settings); break;
        case 2: run_detector<float, 3>(in, settings); break;
        default: run_detector<double, 3>(in, settings); break;
    }
}

}  // namespace smb::fuzz
