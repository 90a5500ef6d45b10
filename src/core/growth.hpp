// SPDX-License-Identifier: MIT
#pragma once
// How the arrays that follow the number of boxes grow. Doubling (std::vector::resize) leaves a
// world whose count crept past a power of two holding twice the memory it needs; reserving the
// exact size reallocates, and copies, at every step that adds a box. A sixteenth of slack sits
// between: rare reallocations, at most a sixteenth held unused. The first fill is exact.

#include <cstddef>

namespace smb::detail {

/// The capacity an array grows to for `size` elements: exact at its first fill, a sixteenth more
/// after.
[[nodiscard]] inline std::size_t capacity_with_slack(std::size_t size, bool first_fill) noexcept {
    return first_fill ? size : size + size / 16;
}

template <class Vector>
void reserve_with_slack(Vector& vector, std::size_t size) {
    if (size > vector.capacity()) vector.reserve(capacity_with_slack(size, vector.empty()));
}

template <class Vector>
void resize_with_slack(Vector& vector, std::size_t size) {
    reserve_with_slack(vector, size);
    vector.resize(size);
}

/// resize_with_slack() for an array that is written over whole after it: where it must grow, its
/// contents are dropped and its block freed first, so that growing copies nothing and never holds
/// the old block and the new one at once.
template <class Vector>
void resize_for_overwrite(Vector& vector, std::size_t size) {
    if (size > vector.capacity()) {
        const bool first_fill = vector.capacity() == 0;
        Vector().swap(vector);
        vector.reserve(capacity_with_slack(size, first_fill));
    }
    vector.resize(size);
}

}  // namespace smb::detail
