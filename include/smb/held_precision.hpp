// SPDX-License-Identifier: MIT
#pragma once
// What a World or Detector held for its last detection: floats or the doubles themselves.

namespace smb {

/// What the last detection held. Double boxes are held as floats, shifted to the middle of the
/// scene and rounded, wherever floats resolve the scene; every pair the floats cannot settle is
/// tested again on the doubles, so the pairs are exact with either.
enum class HeldPrecision {
    none,     ///< nothing detected yet (or no boxes)
    floats,   ///< floats: the input's own (float boxes), or double boxes shifted and rounded
    doubles,  ///< the doubles themselves: floats would not resolve the scene, or
              ///< Pipeline::paper_lists, which holds the boxes as they are
};

}  // namespace smb
