// SPDX-License-Identifier: MIT
#pragma once
// Software prefetch of a whole object. A box of doubles (48 bytes in 3D) straddles two cache
// lines every other time, and asking for its first byte alone leaves the second line to miss
// when the box is read.

namespace smb::detail {

template <class T>
inline void prefetch_whole(const T* object) noexcept {
    __builtin_prefetch(object);
    if constexpr (sizeof(T) > 1) __builtin_prefetch(reinterpret_cast<const char*>(object) + sizeof(T) - 1);
}

}  // namespace smb::detail
