// SPDX-License-Identifier: MIT
// The proxies' life and the pair cache: smb's pair events become the cache's additions and
// removals, so that a pair (and its contact manifold) lives exactly while its boxes overlap.

#include "smb/bullet/broadphase.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

#include "bullet/proxy.hpp"

namespace smb::bullet {

namespace {

/// A static-class proxy that moved is held dynamic until it has kept still this many steps, so
/// that a kinematic body pushed every step does not make smb index its statics again each step.
constexpr std::uint32_t steps_before_static = 8;

}  // namespace

Box<float, 3> detail::checked_box(const btVector3& min, const btVector3& max, const char* what) {
    const Box<float, 3> box = box_of(min, max);
    if (!is_valid(box)) {
        throw InvalidBoxError(std::string("smb::bullet::Broadphase::") + what +
                              ": the AABB has a NaN or infinite coordinate, or min > max");
    }
    return box;
}

Broadphase::Broadphase(const WorldSettings& settings, btOverlappingPairCache* pair_cache)
    : world_(settings), cache_(pair_cache) {
    if (cache_ == nullptr) {
        owned_cache_ = std::make_unique<btHashedOverlappingPairCache>();
        cache_ = owned_cache_.get();
    }
}

Broadphase::~Broadphase() = default;

Broadphase::Proxy& Broadphase::own(const btBroadphaseProxy* proxy) const {
    if (proxy != nullptr && proxy->m_uniqueId >= 0) {
        const auto id = static_cast<std::size_t>(proxy->m_uniqueId);
        if (id < slots_.size() && slots_[id].get() == proxy && slots_[id]->alive) return *slots_[id];
    }
    throw UnknownIdError("smb::bullet::Broadphase: the proxy was not created by this broad phase, or was destroyed");
}

Broadphase::Proxy* Broadphase::live(BoxId id) const noexcept {
    if (id >= slots_.size()) return nullptr;
    Proxy* proxy = slots_[id].get();
    return proxy != nullptr && proxy->alive ? proxy : nullptr;
}

btBroadphaseProxy* Broadphase::createProxy(const btVector3& aabbMin, const btVector3& aabbMax, int /*shapeType*/,
                                           void* userPtr, int collisionFilterGroup, int collisionFilterMask,
                                           btDispatcher* /*dispatcher*/) {
    const Box<float, 3> box = detail::checked_box(aabbMin, aabbMax, "createProxy");
    std::uint32_t id = 0;
    if (!free_ids_.empty()) {
        id = free_ids_.back();
    } else {
        if (slots_.size() >= static_cast<std::size_t>(std::numeric_limits<int>::max())) {
            throw ArgumentError("smb::bullet::Broadphase::createProxy: too many proxies");
        }
        id = static_cast<std::uint32_t>(slots_.size());
        slots_.push_back(std::make_unique<Proxy>());
        free_ids_.push_back(id);  // so that a throw below leaves the new slot free
    }
    world_.insert(id, box);
    free_ids_.pop_back();

    Proxy& proxy = *slots_[id];
    proxy.m_clientObject = userPtr;
    proxy.m_collisionFilterGroup = collisionFilterGroup;
    proxy.m_collisionFilterMask = collisionFilterMask;
    proxy.m_aabbMin = aabbMin;
    proxy.m_aabbMax = aabbMax;
    proxy.m_uniqueId = static_cast<int>(id);
    proxy.filter = Filter{};
    proxy.calm_steps = 0;
    proxy.alive = true;
    proxy.moved = false;
    proxy.static_class = false;
    proxy.held_static = false;
    proxy.restless = false;
    proxy.partners.clear();
    ++live_;
    changed_ = true;
    // The bits reach smb at the next calculateOverlappingPairs (sync_filters), as later changes
    // to them do.
    return &proxy;
}

void Broadphase::destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) {
    Proxy& own_proxy = own(proxy);
    remove_pairs_of(own_proxy, dispatcher);
    const auto id = static_cast<std::uint32_t>(own_proxy.m_uniqueId);
    retired_ids_.reserve(retired_ids_.size() + 1);
    world_.remove(id);
    retired_ids_.push_back(id);
    own_proxy.alive = false;
    own_proxy.m_clientObject = nullptr;
    --live_;
    changed_ = true;
}

namespace {

void erase_partner(std::vector<std::uint32_t>& partners, std::uint32_t id) {
    const auto at = std::find(partners.begin(), partners.end(), id);
    if (at == partners.end()) return;
    *at = partners.back();
    partners.pop_back();
}

}  // namespace

void Broadphase::remove_pairs_of(Proxy& proxy, btDispatcher* dispatcher) {
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
        erase_partner(partner->partners, id);
        --pairs_held_;
        if (cache_is_ours) cache_->removeOverlappingPair(&proxy, partner, dispatcher);
    }
}

void Broadphase::setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax,
                         btDispatcher* /*dispatcher*/) {
    Proxy& own_proxy = own(proxy);
    (void)detail::checked_box(aabbMin, aabbMax, "setAabb");
    // btCollisionWorld sets every object's box at every step, resting or not: an unchanged box
    // costs nothing further.
    if (own_proxy.m_aabbMin == aabbMin && own_proxy.m_aabbMax == aabbMax) return;
    if (!own_proxy.moved) {
        moved_.push_back(static_cast<std::uint32_t>(own_proxy.m_uniqueId));
        own_proxy.moved = true;
    }
    own_proxy.m_aabbMin = aabbMin;
    own_proxy.m_aabbMax = aabbMax;
    changed_ = true;
}

void Broadphase::getAabb(btBroadphaseProxy* proxy, btVector3& aabbMin, btVector3& aabbMax) const {
    const Proxy& own_proxy = own(proxy);
    aabbMin = own_proxy.m_aabbMin;
    aabbMax = own_proxy.m_aabbMax;
}

void Broadphase::flush_moves() {
    if (moved_.empty()) return;
    move_ids_.clear();
    move_boxes_.clear();
    for (const std::uint32_t id : moved_) {
        Proxy* proxy = live(id);
        if (proxy == nullptr) continue;
        move_ids_.push_back(id);
        move_boxes_.push_back(detail::box_of(proxy->m_aabbMin, proxy->m_aabbMax));
    }
    world_.update(move_ids_, move_boxes_);
    for (const std::uint32_t id : moved_) {
        Proxy* proxy = live(id);
        if (proxy == nullptr) continue;
        proxy->moved = false;
        proxy->calm_steps = 0;
        if (proxy->held_static) {
            world_.set_static(id, false);
            proxy->held_static = false;
        }
        if (proxy->static_class && !proxy->restless) {
            restless_.push_back(id);
            proxy->restless = true;
        }
    }
    moved_.clear();
}

void Broadphase::sync_filters() {
    for (std::size_t id = 0; id < slots_.size(); ++id) {
        Proxy* proxy = live(id);
        if (proxy == nullptr) continue;
        const Filter filter = detail::filter_of(proxy->m_collisionFilterGroup, proxy->m_collisionFilterMask);
        if (filter == proxy->filter) continue;
        world_.set_filter(id, filter);
        proxy->filter = filter;
        proxy->static_class = detail::is_static_class(proxy->m_collisionFilterGroup, proxy->m_collisionFilterMask);
        if (proxy->held_static && !proxy->static_class) {
            world_.set_static(id, false);
            proxy->held_static = false;
        }
        if (proxy->static_class && !proxy->held_static && !proxy->restless) {
            // A new static object is held static at once: most never move.
            world_.set_static(id, true);
            proxy->held_static = true;
        }
        changed_ = true;
    }
}

void Broadphase::set_callback_mode(bool callback_mode) {
    callback_mode_ = callback_mode;
    changed_ = true;
    if (!callback_mode_) {
        world_.set_pair_predicate({});
        return;  // sync_filters gives the bits back to smb
    }
    // Bullet's cache asks the callback alone, bits or not: smb must report every overlap.
    for (std::size_t id = 0; id < slots_.size(); ++id) {
        Proxy* proxy = live(id);
        if (proxy == nullptr) continue;
        if (proxy->held_static) world_.set_static(id, false);
        if (proxy->filter != Filter{}) world_.set_filter(id, Filter{});
        proxy->filter = Filter{};
        proxy->held_static = false;
        proxy->static_class = false;
    }
    world_.set_pair_predicate([this](BoxId a, BoxId b) {
        Proxy* proxy_a = live(a);
        Proxy* proxy_b = live(b);
        return proxy_a != nullptr && proxy_b != nullptr && cache_->needsBroadphaseCollision(proxy_a, proxy_b);
    });
}

void Broadphase::settle_restless_statics() {
    std::size_t kept = 0;
    for (const std::uint32_t id : restless_) {
        Proxy* proxy = live(id);
        if (proxy == nullptr) continue;
        if (!proxy->static_class) {
            proxy->restless = false;
            continue;
        }
        if (++proxy->calm_steps >= steps_before_static) {
            world_.set_static(id, true);
            proxy->held_static = true;
            proxy->restless = false;
            continue;
        }
        restless_[kept++] = id;
    }
    restless_.resize(kept);
}

void Broadphase::apply_pair_events(btDispatcher* dispatcher) {
    // A callback (a ghost object's pair callback) may create or destroy proxies on the way:
    // every pair is looked up again, and a destroyed proxy's pairs left the cache with it.
    // The partners and the count are kept before the cache is called, so that they hold what
    // the cache holds should a callback destroy a proxy inside the call.
    for (const Pair& pair : events_.ended()) {
        Proxy* a = live(pair.a);
        Proxy* b = live(pair.b);
        if (a == nullptr || b == nullptr) continue;  // removed with the proxy destroyed
        erase_partner(a->partners, static_cast<std::uint32_t>(pair.b));
        erase_partner(b->partners, static_cast<std::uint32_t>(pair.a));
        --pairs_held_;
        cache_->removeOverlappingPair(a, b, dispatcher);
    }
    for (const Pair& pair : events_.begun()) {
        Proxy* a = live(pair.a);
        Proxy* b = live(pair.b);
        if (a == nullptr || b == nullptr) continue;
        // Ids are the proxies' m_uniqueId, an int: they fit the partner lists' 32 bits.
        a->partners.push_back(static_cast<std::uint32_t>(pair.b));
        b->partners.push_back(static_cast<std::uint32_t>(pair.a));
        ++pairs_held_;
        // A cache may refuse a pair (btNullPairCache refuses all): then it is not held.
        if (cache_->addOverlappingPair(a, b) == nullptr && a->alive && b->alive) {
            erase_partner(a->partners, static_cast<std::uint32_t>(pair.b));
            erase_partner(b->partners, static_cast<std::uint32_t>(pair.a));
            --pairs_held_;
        }
    }
}

void Broadphase::calculateOverlappingPairs(btDispatcher* dispatcher) {
    // Filters first, so that a static proxy that moved since is held dynamic by flush_moves.
    const bool callback_mode = cache_->getOverlapFilterCallback() != nullptr;
    if (callback_mode != callback_mode_) set_callback_mode(callback_mode);
    if (!callback_mode_) sync_filters();
    flush_moves();
    // With nothing changed the pairs are those the cache holds. A filter callback may change its
    // mind at any step, so it is asked at every one.
    if (changed_ || callback_mode_) {
        pairs_.clear();
        world_.detect(pairs_, events_);
        const std::size_t retired_before = retired_ids_.size();
        changed_ = false;
        apply_pair_events(dispatcher);
        // The events named the ids destroyed before the detection for the last time.
        free_ids_.insert(free_ids_.end(), retired_ids_.begin(),
                         retired_ids_.begin() + static_cast<std::ptrdiff_t>(retired_before));
        retired_ids_.erase(retired_ids_.begin(), retired_ids_.begin() + static_cast<std::ptrdiff_t>(retired_before));
    }
    settle_restless_statics();
}

}  // namespace smb::bullet
