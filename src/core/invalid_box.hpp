// SPDX-License-Identifier: MIT
#pragma once
// The message of the InvalidBoxError a World or a Detector throws: what is wrong with the box.

#include <cmath>
#include <concepts>
#include <string>

#include "core/shortest_number.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

/// Names the first axis on which `box` (under id `id`) is invalid, and how.
template <std::floating_point Real, int Dim>
std::string describe_invalid_box(BoxId id, const Box<Real, Dim>& box) {
    const std::string start = "box " + std::to_string(id) + " is invalid: ";
    for (int k = 0; k < Dim; ++k) {
        const std::string axis(1, "xyz"[k]);
        const std::string lo = shortest_number(box.min[k]);
        const std::string hi = shortest_number(box.max[k]);
        if (!std::isfinite(box.min[k]) || !std::isfinite(box.max[k]))
            return start + axis + " range [" + lo + ", " + hi + "] has a NaN or infinite coordinate";
        if (!(box.min[k] <= box.max[k])) return start + axis + "min " + lo + " > " + axis + "max " + hi;
    }
    return start;
}

}  // namespace smb::detail
