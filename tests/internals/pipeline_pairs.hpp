// SPDX-License-Identifier: MIT
#pragma once
// One detection of the persistent cuts straight from its pipeline, for the tests that reach
// below the engine: its pairs collected through a PairOutput and sorted, to compare with a brute
// force.

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "core/pair_output.hpp"
#include "cuts/persistent_cut_pipeline.hpp"
#include "smb/profile.hpp"
#include "smb/settings.hpp"

namespace smb::detail {

/// The pairs of one detection of `boxes` by `pipeline`, sorted.
template <class Real, int Dim, class Input>
std::vector<Pair> detected(PersistentCutPipeline<Real, Dim, Input>& pipeline, std::span<const Box<Input, Dim>> boxes,
                           const DetectionSettings& settings = {}) {
    std::vector<Pair> pairs;
    std::vector<Pair> chunk;
    std::size_t count = 0;
    const PairSink sink([&](std::span<const Pair> run) { pairs.insert(pairs.end(), run.begin(), run.end()); });
    PairOutput output(chunk, 4096, sink, count);
    DetectProfile profile;
    pipeline.detect(boxes, {}, settings, output, profile);
    output.flush();
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

}  // namespace smb::detail
