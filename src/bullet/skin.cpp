// SPDX-License-Identifier: MIT
// The skin (smb/bullet/broadphase.hpp): the World's pairs of fat boxes (the candidates) are
// tested on the proxies' own boxes before they reach the cache, so that boxes jittering inside
// their fat boxes cost a pass over the candidates instead of a detection. Exact because every box
// lies inside its fat box: two boxes that overlap have fat boxes that overlap.

#include "bullet/broadphase_impl.hpp"
#include "core/tuning.hpp"

namespace smb::bullet {

float Broadphase::Impl::next_skin(std::uint32_t id) const {
    // A box that left its fat box by more than a skin moves fast and would leave any skin at the
    // next step, where its fat box would only bring the World more pairs. One that left by less
    // drifts, and a new skin holds it for a while; longer, the thicker the skin, but a thick
    // skin on the boxes of an avalanche brings the World as many pairs again.
    if (!detail::contains(detail::grown(fat_boxes_[id], skin_), boxes_[id])) return 0;
    return step_ - fat_since_[id] >= smb::detail::tuning::bullet_steps_before_creeping
               ? smb::detail::tuning::bullet_creeping_skins * skin_
               : skin_;
}

void Broadphase::Impl::flush_moves() {
    if (moved_.empty()) return;
    move_ids_.clear();
    move_boxes_.clear();
    for (const std::uint32_t id : moved_) {
        // A proxy destroyed since has an empty box, inside any fat box.
        if (detail::contains(fat_boxes_[id], boxes_[id])) continue;
        move_ids_.push_back(id);
        move_boxes_.push_back(detail::grown(boxes_[id], next_skin(id)));
    }
    if (!move_ids_.empty()) world_.update(move_ids_, move_boxes_);
    unlist(moved_, detail::moved_mark);
    for (std::size_t i = 0; i < move_ids_.size(); ++i) {
        const auto id = static_cast<std::uint32_t>(move_ids_[i]);
        fat_boxes_[id] = move_boxes_[i];
        fat_since_[id] = step_;
        if ((marks_[id] & detail::fresh_mark) == 0) fresh_.push_back(id);
        if ((marks_[id] & detail::stale_mark) == 0) stale_.push_back(id);
        marks_[id] |= detail::fresh_mark | detail::stale_mark;
        Proxy& proxy = *slots_[id];
        proxy.calm_steps = 0;
        if (proxy.held_static) hold_static(proxy, false);
        if (proxy.static_class && !proxy.restless) {
            restless_.push_back(id);
            proxy.restless = true;
        }
    }
}

bool Broadphase::Impl::hold_pair(Proxy& a, Proxy& b) {
    // Ids are the proxies' m_uniqueId, an int: they fit the partner lists' 32 bits.
    const auto id_a = static_cast<std::uint32_t>(a.m_uniqueId);
    const auto id_b = static_cast<std::uint32_t>(b.m_uniqueId);
    // The partners and the count are kept before the cache is called, so that they hold what the
    // cache holds should a callback destroy a proxy inside the call.
    a.partners.push_back(id_b);
    b.partners.push_back(id_a);
    ++pairs_held_;
    if (cache_->addOverlappingPair(&a, &b) != nullptr) return true;
    // A cache may refuse a pair (btNullPairCache refuses all): then it is not held.
    if (a.alive && b.alive) {
        detail::erase_partner(a.partners, id_b);
        detail::erase_partner(b.partners, id_a);
        --pairs_held_;
    }
    return false;
}

void Broadphase::Impl::drop_pair(Proxy& a, Proxy& b, btDispatcher* dispatcher) {
    detail::erase_partner(a.partners, static_cast<std::uint32_t>(b.m_uniqueId));
    detail::erase_partner(b.partners, static_cast<std::uint32_t>(a.m_uniqueId));
    --pairs_held_;
    cache_->removeOverlappingPair(&a, &b, dispatcher);
}

void Broadphase::Impl::test_candidates(btDispatcher* dispatcher) {
    for (Candidate& candidate : candidates_) test_candidate(candidate, dispatcher);
}

void Broadphase::Impl::settle_candidate(Candidate& candidate, bool overlap, btDispatcher* dispatcher) {
    // The cache's callbacks may create and destroy proxies on the way: boxes_ may grow (it is
    // indexed afresh for every candidate), a destroyed proxy's box pairs with nothing and its
    // pairs left the cache with it, and a proxy created has no candidate before the next
    // detection. The candidates themselves change only in the passes that call this.
    if (!overlap) {
        drop_if_held(candidate, dispatcher);
        candidate.held = Held::apart;
        return;
    }
    Proxy* a = live(candidate.a);
    Proxy* b = live(candidate.b);
    if (a == nullptr || b == nullptr) return;  // not reached: a destroyed proxy's box is empty
    if (callback_mode_) {
        // A filter callback may change its mind at any step: it is asked at every one, as the
        // cache asks it for every pair.
        const bool wanted = cache_->needsBroadphaseCollision(a, b);
        if (wanted == (candidate.held == Held::held)) return;
        if (!wanted) {
            drop_pair(*a, *b, dispatcher);
            candidate.held = Held::apart;
            return;
        }
    }
    candidate.held = hold_pair(*a, *b) ? Held::held : Held::refused;
}

}  // namespace smb::bullet
