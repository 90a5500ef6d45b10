// SPDX-License-Identifier: MIT
#pragma once
// What the broad phase keeps per proxy beside Bullet's own fields.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "bullet/broadphase_impl.hpp"
#include "smb/box.hpp"
#include "smb/errors.hpp"
#include "smb/filter.hpp"

namespace smb::bullet {

struct Broadphase::Impl::Proxy : btBroadphaseProxy {
    /// Steps since the box last moved, for a static-class proxy held dynamic (restless_).
    std::uint32_t calm_steps = 0;
    bool alive = false;
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

namespace detail {
/// UnknownIdError, out of the way of the calls that check their proxy.
[[noreturn]] void throw_unknown_proxy();

/// marks_: the id is listed in fresh_, in stale_, in moved_, in changed_ids_; its proxy is alive.
inline constexpr std::uint8_t fresh_mark = 1;
inline constexpr std::uint8_t stale_mark = 2;
inline constexpr std::uint8_t moved_mark = 4;
inline constexpr std::uint8_t changed_mark = 8;
inline constexpr std::uint8_t alive_mark = 16;

/// smb::overlaps without an early exit: the passes over the candidates meet pairs apart along
/// any axis, in no order a branch predictor learns. The boxes hold no NaN (checked_box), so
/// `<=` says what `!(>)` says.
[[nodiscard]] inline bool overlaps_branchless(const Box<float, 3>& a, const Box<float, 3>& b) noexcept {
    return static_cast<bool>(static_cast<int>(a.min[0] <= b.max[0]) & static_cast<int>(b.min[0] <= a.max[0]) &
                             static_cast<int>(a.min[1] <= b.max[1]) & static_cast<int>(b.min[1] <= a.max[1]) &
                             static_cast<int>(a.min[2] <= b.max[2]) & static_cast<int>(b.min[2] <= a.max[2]));
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

[[nodiscard]] inline bool contains(const Box<float, 3>& outer, const Box<float, 3>& inner) noexcept {
    for (int k = 0; k < 3; ++k) {
        if (inner.min[k] < outer.min[k] || inner.max[k] > outer.max[k]) return false;
    }
    return true;
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

// Inline: setAabb and the passes over the proxies and the candidates call these for every one.
inline Broadphase::Impl::Proxy& Broadphase::Impl::own(const btBroadphaseProxy* proxy) const {
    if (proxy != nullptr && proxy->m_uniqueId >= 0) {
        const auto id = static_cast<std::size_t>(proxy->m_uniqueId);
        if (id < slots_.size() && slots_[id].get() == proxy && slots_[id]->alive) return *slots_[id];
    }
    detail::throw_unknown_proxy();
}

inline Broadphase::Impl::Proxy* Broadphase::Impl::live(BoxId id) const noexcept {
    if (id >= slots_.size()) return nullptr;
    Proxy* proxy = slots_[id].get();
    return proxy != nullptr && proxy->alive ? proxy : nullptr;
}

inline void Broadphase::Impl::mark_changed(std::uint32_t id) {
    if ((marks_[id] & detail::changed_mark) != 0) return;
    marks_[id] |= detail::changed_mark;
    changed_ids_.push_back(id);
}

inline void Broadphase::Impl::test_candidate(Candidate& candidate, btDispatcher* dispatcher) {
    // Every calculateOverlappingPairs leaves each candidate's standing as its boxes are: while
    // neither box changes, it stands (in a pile partly asleep, most candidates).
    if (!test_all_ && ((marks_[candidate.a] | marks_[candidate.b]) & detail::changed_mark) == 0) return;
    test_new_candidate(candidate, dispatcher);
}

inline void Broadphase::Impl::test_new_candidate(Candidate& candidate, btDispatcher* dispatcher) {
    const bool overlap = detail::overlaps_branchless(boxes_[candidate.a], boxes_[candidate.b]);
    // Most candidates stay as they were: apart and still apart, or held (or refused) and still
    // overlapping. A filter callback is asked at every step.
    if (!callback_mode_ && overlap == (candidate.held != Held::apart)) return;
    settle_candidate(candidate, overlap, dispatcher);
}

}  // namespace smb::bullet
