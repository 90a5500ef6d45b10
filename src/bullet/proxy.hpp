// SPDX-License-Identifier: MIT
#pragma once
// What the broad phase keeps per proxy beside Bullet's own fields.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "smb/box.hpp"
#include "smb/bullet/broadphase.hpp"
#include "smb/errors.hpp"
#include "smb/filter.hpp"

namespace smb::bullet {

struct Broadphase::Proxy : btBroadphaseProxy {
    /// The filter smb holds for this box (the default while the cache has a filter callback).
    Filter filter{};
    /// Steps since the box last moved, for a static-class proxy held dynamic (restless_).
    std::uint32_t calm_steps = 0;
    bool alive = false;
    /// Listed in moved_ since the last flush.
    bool moved = false;
    /// Its bits keep it from pairing with any other proxy of its kind (Bullet's static and
    /// kinematic objects).
    bool static_class = false;
    /// smb holds it as a static box.
    bool held_static = false;
    /// Listed in restless_.
    bool restless = false;
    /// The proxies this one is paired with in the cache (this broad phase's additions), so that
    /// destroyProxy removes its pairs one by one instead of scanning the whole cache.
    std::vector<std::uint32_t> partners;
};

// Here, inline: every pass over the candidates and the proxies asks it.
inline Broadphase::Proxy* Broadphase::live(BoxId id) const noexcept {
    if (id >= slots_.size()) return nullptr;
    Proxy* proxy = slots_[id].get();
    return proxy != nullptr && proxy->alive ? proxy : nullptr;
}

namespace detail {

/// marks_: the id is listed in fresh_, in stale_.
inline constexpr std::uint8_t fresh_mark = 1;
inline constexpr std::uint8_t stale_mark = 2;

/// (a, b) order of candidates, the order of the pairs of smb's events.
[[nodiscard]] inline bool comes_before(std::uint32_t a0, std::uint32_t b0, std::uint32_t a1,
                                       std::uint32_t b1) noexcept {
    return a0 != a1 ? a0 < a1 : b0 < b1;
}

/// Static and kinematic objects as btCollisionWorld files them (group StaticFilter, mask every bit
/// but StaticFilter), and any proxy whose group holds only StaticFilter and KinematicFilter bits
/// and whose mask holds neither. For any two such proxies a and b, a.group & b.mask is 0 or
/// b.group & a.mask is 0, so Bullet never pairs them and smb may hold both as static boxes.
[[nodiscard]] inline bool is_static_class(int group, int mask) noexcept {
    constexpr int fixed = btBroadphaseProxy::StaticFilter | btBroadphaseProxy::KinematicFilter;
    if (group == btBroadphaseProxy::StaticFilter) return (mask & btBroadphaseProxy::StaticFilter) == 0;
    return group != 0 && (group & ~fixed) == 0 && (mask & fixed) == 0;
}

[[nodiscard]] inline Filter filter_of(int group, int mask) noexcept {
    return Filter{static_cast<std::uint32_t>(group), static_cast<std::uint32_t>(mask)};
}

[[nodiscard]] inline Box<float, 3> box_of(const btVector3& min, const btVector3& max) noexcept {
    return Box<float, 3>{{min.x(), min.y(), min.z()}, {max.x(), max.y(), max.z()}};
}

/// The box grown by `skin` on every side. Rounding is monotone, so it holds the box.
[[nodiscard]] inline Box<float, 3> grown(const Box<float, 3>& box, float skin) noexcept {
    Box<float, 3> fat = box;
    for (int k = 0; k < 3; ++k) {
        fat.min[k] -= skin;
        fat.max[k] += skin;
    }
    return fat;
}

/// A box that overlaps no box (min > max on every axis): a destroyed proxy's.
[[nodiscard]] inline Box<float, 3> empty_box() noexcept {
    constexpr float inf = std::numeric_limits<float>::infinity();
    return Box<float, 3>{{inf, inf, inf}, {-inf, -inf, -inf}};
}

inline void erase_partner(std::vector<std::uint32_t>& partners, std::uint32_t id) {
    const auto at = std::find(partners.begin(), partners.end(), id);
    if (at == partners.end()) return;
    *at = partners.back();
    partners.pop_back();
}

/// The box, or InvalidBoxError naming `what` when it has NaN, infinity or min > max.
[[nodiscard]] Box<float, 3> checked_box(const btVector3& min, const btVector3& max, const char* what);

}  // namespace detail
}  // namespace smb::bullet
