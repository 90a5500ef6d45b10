#pragma once
// The message of the InvalidBoxError a World or a Detector throws: what is wrong with the box.

#include <cmath>
#include <concepts>
#include <sstream>
#include <string>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

/// Names the first axis on which `box` (under id `id`) is invalid, and how.
template <std::floating_point Real, int Dim>
std::string describe_invalid_box(BoxId id, const Box<Real, Dim>& box) {
    std::ostringstream out;
    out.precision(17);
    out << "box " << id << " is invalid: ";
    for (int k = 0; k < Dim; ++k) {
        const char axis = "xyz"[k];
        if (!std::isfinite(box.min[k]) || !std::isfinite(box.max[k])) {
            out << axis << " range [" << box.min[k] << ", " << box.max[k]
                << "] has a NaN or infinite coordinate";
            return out.str();
        }
        if (!(box.min[k] <= box.max[k])) {
            out << axis << "min " << box.min[k] << " > " << axis << "max " << box.max[k];
            return out.str();
        }
    }
    return out.str();
}

}  // namespace smb::detail
