// SPDX-License-Identifier: MIT
#pragma once
// How the paper's pipeline grows its lists from one detection to the next: room for what
// arrives without doubling, and arrivals merged in place.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "paper/axis_entry.hpp"

namespace smb::detail {

/// Grows `list` to hold `length` items with a sixteenth to spare, and gives back what is more
/// than a quarter above it: vectors that double would hold up to twice the lists' bytes, and
/// more after N has shrunk.
template <class Vector>
void fit_capacity(Vector& list, std::size_t length) {
    if (length > list.capacity()) {
        list.reserve(length + length / 16);
    } else if (list.capacity() > length + length / 4 && list.capacity() > 4096) {
        Vector smaller;
        smaller.reserve(std::max(length, list.size()) + length / 16);
        smaller.assign(list.begin(), list.end());
        list.swap(smaller);
    }
}

/// Merges the sorted `arrivals` into the sorted `list` in place, from the back.
template <class Entry>
void merge_from_back(std::vector<Entry>& list, const std::vector<Entry>& arrivals) {
    std::size_t kept = list.size();
    std::size_t arrived = arrivals.size();
    list.resize(kept + arrived);
    std::size_t out = list.size();
    while (arrived > 0) {
        if (kept > 0 && entry_less(arrivals[arrived - 1], list[kept - 1])) {
            list[--out] = list[--kept];
        } else {
            list[--out] = arrivals[--arrived];
        }
    }
}

}  // namespace smb::detail
