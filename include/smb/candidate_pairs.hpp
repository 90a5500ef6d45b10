// SPDX-License-Identifier: MIT
#pragma once
// The Verlet list of a Detector with a skin, as the caller reads it (Detector::candidates()).

#include <span>

#include "smb/pair.hpp"

namespace smb {

/// The candidate pairs a Detector with a skin keeps between detections (a Verlet list), as they
/// stood after the last detect(). DEM and molecular dynamics codes compute their forces over
/// such a list, with a cut-off, instead of over the overlapping pairs alone.
///
/// Each box i of the last detect()'s array lies inside its fat box: the box it had when the
/// candidates were last rebuilt, or when it last left its fat box (or arrived), grown by the
/// skin on every side (rounded outwards to floats). `pairs` holds every pair of indices whose
/// fat boxes overlap (closed convention), each once, with Pair::a < Pair::b, and nothing else.
/// Hence:
/// - every pair of boxes that overlap is in `pairs` (the detection's pairs are a subset);
/// - every pair of boxes that overlap once each is grown by `margin` on every side is in
///   `pairs`: `margin` is the least distance, over the boxes and their faces, from a box to its
///   fat box, less the float rounding of the held boxes (never negative; about the skin right
///   after a rebuild, shrinking as boxes move towards the faces of their fat boxes);
/// - a pair is in `pairs` only if its fat boxes overlap; a box that keeps its size stays within
///   one skin of where its fat box was made, so the two boxes of a pair, each grown by two
///   skins, overlap.
///
/// Order: unspecified, but the same calls give the same pairs in the same order, whatever
/// DetectionSettings::threads says. Use smb::sort_pairs on a copy for (a, b) order.
///
/// `available` is false, and `pairs` empty, when the last detection did not run on the skin
/// list: no skin (DetectorSettings::skin == 0); no detect() since construction or clear(); an
/// empty array; a detect() that threw; a detection with filters that left some boxes out
/// (their indices were not the caller's); a periodic detection (smb/periodic.hpp); the
/// detector holding doubles for a scene that floats cannot resolve (Detector::last_precision());
/// and the detections where it stepped aside from the skin because the boxes moved farther
/// than the skin, or the fat boxes made more than about 32 candidates per box
/// (DetectorSettings::skin). The caller then falls back on the
/// detection's pairs, which are exact in every case.
struct CandidatePairs {
    std::span<const Pair> pairs;
    double margin = 0;
    bool available = false;
};

}  // namespace smb
