// SPDX-License-Identifier: MIT
// The candidates between detections: when few fat boxes change in a step, their candidates are
// found through an index of the fat boxes and merged into the list instead of detecting every
// pair again. Exact because the candidates stay every pair of fat boxes that overlap and pass
// the filters: a pair whose fat boxes did not change keeps its standing, and every pair with a
// changed fat box is found again (through the index, or one by one among the stale boxes).

#include <algorithm>

#include "bullet/broadphase_impl.hpp"
#include "core/pair_key_sort.hpp"
#include "smb/filter.hpp"

namespace smb::bullet {

namespace {

using Candidate = BroadphasePool::Candidate;

/// (a, b) order of candidates, the order of the detection's pairs once sorted.
[[nodiscard]] bool comes_before(const Candidate& x, const Candidate& y) noexcept {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
}

[[nodiscard]] bool same_pair(const Candidate& x, const Candidate& y) noexcept { return x.a == y.a && x.b == y.b; }

}  // namespace

void Broadphase::Impl::build_index() {
    index_ids_.clear();
    index_boxes_.clear();
    for (std::size_t id = 0; id < slots_.size(); ++id) {
        if (live(id) == nullptr) continue;
        index_ids_.push_back(id);
        index_boxes_.push_back(fat_boxes_[id]);
    }
    index_.build(index_ids_, index_boxes_);
    unlist(stale_, detail::stale_mark);
    index_current_ = true;
}

void Broadphase::Impl::update_fresh_candidates(btDispatcher* dispatcher) {
    // Stale boxes are tested one by one for every fresh box: past a limit the index is built
    // again (linear in the boxes, a fraction of a detection).
    const std::size_t stale_limit = std::max<std::size_t>(64, live_ / 8);
    if (!index_current_ || stale_.size() > stale_limit) build_index();
    // Between detections no proxy is created, destroyed or refiltered (each makes the next
    // calculateOverlappingPairs detect): the proxies named here are alive.
    const auto found = [this](std::uint32_t a, std::uint32_t b) {
        if (callback_mode_ || filters_pass(filters_[a], filters_[b]))
            found_.push_back(Candidate{std::min(a, b), std::max(a, b), Held::apart});
    };
    found_.clear();
    // The stale boxes side by side, read once per fresh box.
    stale_boxes_.clear();
    for (const std::uint32_t id : stale_) stale_boxes_.push_back(fat_boxes_[id]);
    for (const std::uint32_t fresh : fresh_) {
        const Box<float, 3> fat = fat_boxes_[fresh];
        index_.query(fat, hits_);
        for (const BoxId hit : hits_) {
            const auto other = static_cast<std::uint32_t>(hit);
            if (other == fresh || (marks_[other] & detail::stale_mark) != 0) continue;
            found(fresh, other);
        }
        for (std::size_t i = 0; i < stale_.size(); ++i) {
            if (!overlaps(fat, stale_boxes_[i])) continue;
            const std::uint32_t other = stale_[i];
            if (other != fresh) found(fresh, other);
        }
    }
    // Two fresh boxes find each other twice.
    std::sort(found_.begin(), found_.end(), comes_before);
    found_.erase(std::unique(found_.begin(), found_.end(), same_pair), found_.end());

    // The candidates with a fresh end are those found; the others keep their standing. In place,
    // each candidate tested as it is met: one pass, and those found anew go to the end (the list
    // is sorted again before the next detection's merge, reconcile_candidates).
    found_seen_.assign(found_.size(), 0);
    std::size_t kept = 0;
    for (std::size_t i = 0; i < candidates_.size(); ++i) {
        const Candidate candidate = candidates_[i];
        if (((marks_[candidate.a] | marks_[candidate.b]) & detail::fresh_mark) != 0) {
            const auto at = std::lower_bound(found_.begin(), found_.end(), candidate, comes_before);
            if (at == found_.end() || !same_pair(*at, candidate)) {
                drop_if_held(candidate, dispatcher);
                continue;
            }
            found_seen_[static_cast<std::size_t>(at - found_.begin())] = 1;
        }
        candidates_[kept] = candidate;
        test_candidate(candidates_[kept], dispatcher);
        ++kept;
    }
    candidates_.resize(kept);
    for (std::size_t i = 0; i < found_.size(); ++i) {
        if (found_seen_[i] != 0) continue;
        candidates_.push_back(found_[i]);
        test_new_candidate(candidates_.back(), dispatcher);
        candidates_sorted_ = false;
    }
    unlist(fresh_, detail::fresh_mark);
}

void Broadphase::Impl::reconcile_candidates(btDispatcher* dispatcher) {
    smb::detail::sort_pair_keys(pair_keys_, 2 * key_width_, key_spare_, key_counts_);
    if (!candidates_sorted_) std::sort(candidates_.begin(), candidates_.end(), comes_before);
    candidates_sorted_ = true;
    merged_.clear();
    merged_.reserve(pair_keys_.size());
    const auto keep = [this, dispatcher](const Candidate& candidate) {
        merged_.push_back(candidate);
        test_candidate(merged_.back(), dispatcher);
    };
    const int width = key_width_;
    const std::uint64_t low = (std::uint64_t{1} << width) - 1;
    const auto add = [this, dispatcher, width, low](std::uint64_t key) {
        merged_.push_back(
            Candidate{static_cast<std::uint32_t>(key >> width), static_cast<std::uint32_t>(key & low), Held::apart});
        test_new_candidate(merged_.back(), dispatcher);
    };
    // Keys order pairs as comes_before does.
    const std::uint64_t* next = pair_keys_.data();
    const std::uint64_t* const end = next + pair_keys_.size();
    for (const Candidate& candidate : candidates_) {
        const std::uint64_t key = (std::uint64_t{candidate.a} << width) | candidate.b;
        while (next != end && *next < key) add(*next++);
        if (next != end && *next == key) {
            ++next;
            keep(candidate);
            continue;
        }
        drop_if_held(candidate, dispatcher);
    }
    while (next != end) add(*next++);
    candidates_.swap(merged_);
}

}  // namespace smb::bullet
