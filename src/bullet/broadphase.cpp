// SPDX-License-Identifier: MIT
// The proxies' life and the pair cache: the pairs that begin and stop overlapping become the cache's additions and
// removals, so that a pair (and its contact manifold) lives exactly while its boxes overlap.

#include "bullet/broadphase_impl.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>

#include "core/held_box.hpp"
#include "core/tuning.hpp"

namespace smb::bullet {

void detail::throw_unknown_proxy() {
    throw UnknownIdError("smb::bullet::Broadphase: the proxy was not created by this broad phase, or was destroyed");
}

Box<float, 3> detail::checked_box(const btVector3& min, const btVector3& max, const char* what) {
    const Box<float, 3> box = box_of(min, max);
    if (!is_valid(box)) {
        throw InvalidBoxError(std::string("smb::bullet::Broadphase::") + what +
                              ": the AABB has a NaN or infinite coordinate, or min > max");
    }
    return box;
}

Broadphase::Impl::Impl(const WorldSettings& settings, btOverlappingPairCache* pair_cache, float skin)
    : world_(settings), skin_(skin), cache_(pair_cache) {
    if (!std::isfinite(skin) || skin < 0) {
        throw ArgumentError("smb::bullet::Broadphase: the skin must be finite and not negative");
    }
    if (cache_ == nullptr) {
        owned_cache_ = std::make_unique<btHashedOverlappingPairCache>();
        cache_ = owned_cache_.get();
    }
}

btBroadphaseProxy* Broadphase::Impl::createProxy(const btVector3& aabbMin, const btVector3& aabbMax, void* userPtr,
                                                 int collisionFilterGroup, int collisionFilterMask) {
    const Box<float, 3> box = detail::checked_box(aabbMin, aabbMax, "createProxy");
    if (free_ids_.empty()) {
        if (slots_.size() >= static_cast<std::size_t>(std::numeric_limits<int>::max())) {
            throw ArgumentError("smb::bullet::Broadphase::createProxy: too many proxies");
        }
        slots_.push_back(std::make_unique<Proxy>());
        free_ids_.push_back(static_cast<std::uint32_t>(slots_.size() - 1));  // a throw below leaves it free
    }
    const std::uint32_t id = free_ids_.back();
    if (boxes_.size() <= id) {
        boxes_.resize(id + 1, smb::detail::empty_float_box<3>());
        fat_boxes_.resize(id + 1, smb::detail::empty_float_box<3>());
        fat_since_.resize(id + 1, 0);
        filters_.resize(id + 1);
        marks_.resize(id + 1, 0);
    }
    const Box<float, 3> fat = detail::grown(box, skin_);
    world_.insert(id, fat);
    free_ids_.pop_back();
    boxes_[id] = box;
    fat_boxes_[id] = fat;
    fat_since_[id] = step_;

    Proxy& proxy = *slots_[id];
    proxy.m_clientObject = userPtr;
    proxy.m_collisionFilterGroup = collisionFilterGroup;
    proxy.m_collisionFilterMask = collisionFilterMask;
    proxy.m_aabbMin = aabbMin;
    proxy.m_aabbMax = aabbMax;
    proxy.m_uniqueId = static_cast<int>(id);
    proxy.calm_steps = 0;
    proxy.alive = true;
    proxy.static_class = false;
    proxy.held_static = false;
    proxy.restless = false;
    proxy.partners.clear();
    filters_[id] = Filter{};
    marks_[id] |= detail::alive_mark;
    ++live_;
    changed_ = true;
    mark_changed(id);
    // The bits reach smb at the next calculateOverlappingPairs (sync_filters), as later changes
    // to them do.
    return &proxy;
}

void Broadphase::Impl::destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) {
    Proxy& own_proxy = own(proxy);
    remove_pairs_of(own_proxy, dispatcher);
    const auto id = static_cast<std::uint32_t>(own_proxy.m_uniqueId);
    retired_ids_.reserve(retired_ids_.size() + 1);
    world_.remove(id);
    retired_ids_.push_back(id);
    boxes_[id] = smb::detail::empty_float_box<3>();
    mark_changed(id);
    own_proxy.alive = false;
    marks_[id] &= static_cast<std::uint8_t>(~detail::alive_mark);
    own_proxy.m_clientObject = nullptr;
    --live_;
    changed_ = true;
}

void Broadphase::Impl::remove_pairs_of(Proxy& proxy, btDispatcher* dispatcher) {
    const auto id = static_cast<std::uint32_t>(proxy.m_uniqueId);
    // btHashedOverlappingPairCache::removeOverlappingPairsContainingProxy visits every pair of
    // the cache: with 20 bodies taken out of a pile of 10 000 (50 000 pairs) it cost more than the
    // detection of the step. The partners name the proxy's pairs directly, each a hash look-up.
    const bool cache_is_ours = static_cast<std::size_t>(cache_->getNumOverlappingPairs()) == pairs_held_;
    if (!cache_is_ours) cache_->removeOverlappingPairsContainingProxy(&proxy, dispatcher);
    // Taken out first: a callback inside the cache may destroy a partner, which then erases its
    // own pair from the list.
    const std::vector<std::uint32_t> partners = std::move(proxy.partners);
    proxy.partners.clear();
    for (const std::uint32_t partner_id : partners) {
        Proxy* partner = live(partner_id);
        if (partner == nullptr) continue;  // destroyed inside a callback: its pairs went with it
        detail::erase_partner(partner->partners, id);
        --pairs_held_;
        if (cache_is_ours) cache_->removeOverlappingPair(&proxy, partner, dispatcher);
    }
}

void Broadphase::Impl::setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax) {
    Proxy& own_proxy = own(proxy);
    // btCollisionWorld sets every object's box at every step, resting or not: an unchanged box
    // costs nothing further (it was checked when it was set; a NaN never compares equal).
    if (own_proxy.m_aabbMin == aabbMin && own_proxy.m_aabbMax == aabbMax) return;
    const Box<float, 3> box = detail::checked_box(aabbMin, aabbMax, "setAabb");
    const auto id = static_cast<std::uint32_t>(own_proxy.m_uniqueId);
    // Inside its fat box the box changes nothing in the World; flush_moves looks again at those
    // that left it (they may come back before it).
    if ((marks_[id] & detail::moved_mark) == 0 && !detail::contains(fat_boxes_[id], box)) {
        moved_.push_back(id);
        marks_[id] |= detail::moved_mark;
    }
    own_proxy.m_aabbMin = aabbMin;
    own_proxy.m_aabbMax = aabbMax;
    boxes_[id] = box;
    mark_changed(id);
}

void Broadphase::Impl::sync_filters() {
    // Every live proxy's bits, at every step: the liveness and the filter held are read from
    // arrays by id, so that a proxy whose bits did not change costs one cache line of its own
    // (that of Bullet's fields), which matters once the proxies outgrow the caches.
    for (std::size_t id = 0; id < slots_.size(); ++id) {
        if ((marks_[id] & detail::alive_mark) == 0) continue;
        Proxy* proxy = slots_[id].get();
        const Filter filter = detail::filter_of(proxy->m_collisionFilterGroup, proxy->m_collisionFilterMask);
        if (filter == filters_[id]) continue;
        world_.set_filter(id, filter);
        filters_[id] = filter;
        proxy->static_class = detail::is_static_class(proxy->m_collisionFilterGroup, proxy->m_collisionFilterMask);
        if (proxy->held_static && !proxy->static_class) hold_static(*proxy, false);
        // A new static object is held static at once: most never move.
        if (proxy->static_class && !proxy->held_static && !proxy->restless) hold_static(*proxy, true);
        changed_ = true;
    }
}

void Broadphase::Impl::set_callback_mode(bool callback_mode) {
    callback_mode_ = callback_mode;
    changed_ = true;
    test_all_ = true;
    // sync_filters gives the bits back to smb.
    if (!callback_mode_) return;
    // Bullet's cache asks the callback alone, bits or not: smb must report every overlap, and
    // test_candidates asks the callback.
    for (std::size_t id = 0; id < slots_.size(); ++id) {
        Proxy* proxy = live(id);
        if (proxy == nullptr) continue;
        if (proxy->held_static) hold_static(*proxy, false);
        if (filters_[id] != Filter{}) world_.set_filter(id, Filter{});
        filters_[id] = Filter{};
        proxy->static_class = false;
    }
}

void Broadphase::Impl::hold_static(Proxy& proxy, bool held) {
    world_.set_static(static_cast<BoxId>(proxy.m_uniqueId), held);
    proxy.held_static = held;
}

void Broadphase::Impl::settle_restless_statics() {
    std::size_t kept = 0;
    for (const std::uint32_t id : restless_) {
        Proxy* proxy = live(id);
        if (proxy == nullptr) continue;
        if (!proxy->static_class) {
            proxy->restless = false;
            continue;
        }
        if (++proxy->calm_steps >= smb::detail::tuning::bullet_steps_before_static) {
            hold_static(*proxy, true);
            proxy->restless = false;
            continue;
        }
        restless_[kept++] = id;
    }
    restless_.resize(kept);
}

void Broadphase::Impl::calculateOverlappingPairs(btDispatcher* dispatcher) {
    // Filters first, so that a static proxy that moved since is held dynamic by flush_moves.
    const bool callback_mode = cache_->getOverlapFilterCallback() != nullptr;
    if (callback_mode != callback_mode_) set_callback_mode(callback_mode);
    test_all_ = test_all_ || callback_mode_;
    if (!callback_mode_) sync_filters();
    flush_moves();
    // A proxy or a filter changed, or many fat boxes: smb detects the candidates again. A few
    // fat boxes changed: their candidates are found one by one (a detection costs about as much
    // as finding those of a sixteenth of the boxes). No fat box changed: the candidates stand.
    // Then the candidates are tested on the boxes, unless no box changed either (the pairs are
    // those the cache holds); a filter callback may change its mind at any step, so it is asked
    // at every one.
    const std::size_t fresh_limit = std::max<std::size_t>(64, live_ / 16);
    if (changed_ || fresh_.size() > fresh_limit) {
        // The pairs of the detection are merged with the candidates directly: sorted by a radix
        // sort, they cost less than comparing the two lists through hashed partitions. Exact because
        // an id is given out again only after a detection (retired_ids_): a pair of two ids
        // stands for the same two proxies in both lists.
        pair_keys_.clear();
        key_width_ = static_cast<int>(std::bit_width(slots_.size()));  // every id is below slots_.size()
        world_.detect([this](std::span<const Pair> chunk) {
            for (const Pair& pair : chunk) pair_keys_.push_back((pair.a << key_width_) | pair.b);
        });
        const std::size_t retired_before = retired_ids_.size();
        changed_ = false;
        reconcile_candidates(dispatcher);
        index_current_ = false;
        unlist(fresh_, detail::fresh_mark);
        unlist(stale_, detail::stale_mark);
        // The detection named the ids destroyed before it for the last time.
        free_ids_.insert(free_ids_.end(), retired_ids_.begin(),
                         retired_ids_.begin() + static_cast<std::ptrdiff_t>(retired_before));
        retired_ids_.erase(retired_ids_.begin(), retired_ids_.begin() + static_cast<std::ptrdiff_t>(retired_before));
    } else if (!fresh_.empty()) {
        update_fresh_candidates(dispatcher);
    } else if (!changed_ids_.empty() || test_all_) {
        test_candidates(dispatcher);
    }
    unlist(changed_ids_, detail::changed_mark);
    test_all_ = false;
    settle_restless_statics();
    ++step_;
}

// The public interface: each call handed to the implementation, in this file so that the
// calls Bullet makes for every proxy at every step (setAabb, getAabb) inline their bodies.

Broadphase::Broadphase(const WorldSettings& settings, btOverlappingPairCache* pair_cache, float skin)
    : impl_(std::make_unique<Impl>(settings, pair_cache, skin)) {}

Broadphase::~Broadphase() = default;

btBroadphaseProxy* Broadphase::createProxy(const btVector3& aabbMin, const btVector3& aabbMax, int /*shapeType*/,
                                           void* userPtr, int collisionFilterGroup, int collisionFilterMask,
                                           btDispatcher* /*dispatcher*/) {
    return impl_->createProxy(aabbMin, aabbMax, userPtr, collisionFilterGroup, collisionFilterMask);
}

void Broadphase::destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) {
    impl_->destroyProxy(proxy, dispatcher);
}

void Broadphase::setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax,
                         btDispatcher* /*dispatcher*/) {
    impl_->setAabb(proxy, aabbMin, aabbMax);
}

void Broadphase::getAabb(btBroadphaseProxy* proxy, btVector3& aabbMin, btVector3& aabbMax) const {
    const Impl::Proxy& own_proxy = impl_->own(proxy);
    aabbMin = own_proxy.m_aabbMin;
    aabbMax = own_proxy.m_aabbMax;
}

void Broadphase::rayTest(const btVector3& rayFrom, const btVector3& rayTo, btBroadphaseRayCallback& rayCallback,
                         const btVector3& aabbMin, const btVector3& aabbMax) {
    impl_->rayTest(rayFrom, rayTo, rayCallback, aabbMin, aabbMax);
}

void Broadphase::aabbTest(const btVector3& aabbMin, const btVector3& aabbMax, btBroadphaseAabbCallback& callback) {
    impl_->aabbTest(aabbMin, aabbMax, callback);
}

void Broadphase::calculateOverlappingPairs(btDispatcher* dispatcher) { impl_->calculateOverlappingPairs(dispatcher); }

btOverlappingPairCache* Broadphase::getOverlappingPairCache() { return impl_->cache_; }

const btOverlappingPairCache* Broadphase::getOverlappingPairCache() const { return impl_->cache_; }

void Broadphase::getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const {
    impl_->getBroadphaseAabb(aabbMin, aabbMax);
}

void Broadphase::resetPool(btDispatcher* /*dispatcher*/) { impl_->resetPool(); }

void Broadphase::printStats() { impl_->printStats(); }

std::size_t Broadphase::size() const noexcept { return impl_->live_; }

const World<float, 3>& Broadphase::world() const noexcept { return impl_->world_; }

}  // namespace smb::bullet
