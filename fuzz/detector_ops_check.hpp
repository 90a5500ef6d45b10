// SPDX-License-Identifier: MIT
#pragma once
// Sequences of changes to an array of boxes, each followed by a Detector call, on arbitrary
// coordinates (the hostile table and raw bytes of world_ops_check.hpp): the check behind the
// fuzz_detector_ops target and behind the replay of its inputs in the tests.
//
// The array holds only valid boxes; an invalid one is offered in a copy of the array, which the
// detector must refuse naming its index, and must then still give the array's exact pairs.
// Every detection must equal brute force, whatever the detector holds (floats or doubles), with
// or without a skin.

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
using world_ops_detail::check_detection;
using world_ops_detail::decode_box;
using world_ops_detail::decode_coordinate;
using world_ops_detail::kMaxBoxes;

template <typename Real, int Dim>
class DetectorHarness {
public:
    using BoxT = smb::Box<Real, Dim>;

    explicit DetectorHarness(const smb::WorldSettings& settings) : detector_(with_skin(settings)) {}

    void run(ByteReader& in) {
        while (!in.done()) step(in);
        detect_and_compare(false);
    }

private:
    /// The shared settings of the decoding, and for half the inputs a skin
    /// (DetectorSettings::skin), chosen by the chunk size the shared decoding read, so that the
    /// inputs of the corpus keep their meaning: none, a thousandth, half a unit, four units.
    static smb::DetectorSettings with_skin(const smb::DetectionSettings& settings) {
        constexpr std::array<double, 4> kSkins{0.0, 1e-3, 0.5, 4.0};
        return smb::DetectorSettings{settings, kSkins[settings.pair_chunk_size % kSkins.size()]};
    }

    void step(ByteReader& in) {
        switch (in.byte() % 7) {
            case 0:
            case 1:
                append(in);
                break;
            case 2:
                replace(in);
                break;
            case 3:
                swap_remove(in);
                break;
            case 4:
                shift_all(in);
                break;
            case 5:
                detect_and_compare(in.byte() % 2 == 1);
                break;
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
        if (smb::is_valid(box))
            boxes_[index] = box;
        else
            offer_invalid(index, box);
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
        if (index == offered.size())
            offered.push_back(bad);
        else
            offered[index] = bad;
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

        check_detection(expected, detector_.settings(), through_sink,
                        [&](auto& pairs_or_sink) { detector_.detect(boxes_, pairs_or_sink); });
    }

    smb::Detector<Real, Dim> detector_;
    std::vector<BoxT> boxes_;
};

}  // namespace detector_ops_detail

/// Decodes `data` into a detector type, settings (as world operations; one thread: OpenMP's idle
/// threads spin between inputs and slow the fuzzer tenfold, and tests/api/test_detector.cpp checks
/// thread counts against brute force) and changes to its array, and checks every detection;
/// throws std::logic_error at the first broken promise of smb.
inline void check_detector_operations(const std::uint8_t* data, std::size_t size) {
    world_ops_detail::run_decoded<detector_ops_detail::DetectorHarness>(data, size);
}

}  // namespace smb::fuzz
