// SPDX-License-Identifier: MIT
#pragma once
// How the arrays that follow the number of boxes grow. std::vector::resize doubles its capacity
// when it outgrows it, which would leave a world whose box count crept past a power of two
// holding twice the memory it needs; reserve() with the exact size instead reallocates, and
// copies, on every step that adds a box. A sixteenth of slack sits between: a world whose size
// wanders step by step reallocates rarely and holds at most a sixteenth more than it uses. The
// first fill is exact: a world that never changes size pays nothing.

#include <cstddef>

namespace smb::detail {

template <class Vector>
void reserve_with_slack(Vector& vector, std::size_t size) {
    if (size > vector.capacity()) vector.reserve(vector.empty() ? size : size + size / 16);
}

template <class Vector>
void resize_with_slack(Vector& vector, std::size_t size) {
    reserve_with_slack(vector, size);
    vector.resize(size);
}

}  // namespace smb::detail
