// SPDX-License-Identifier: MIT
#include "smb/pair_events.hpp"

#include <algorithm>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "events/body_fates.hpp"
#include "events/pair_partitions.hpp"
#include "events/pair_radix_sort.hpp"
#include "events/partition_diff.hpp"

namespace smb {

namespace detail {

/// The previous list, hashed into partitions; the calls made since; the last events. An update
/// builds the next list and the events in scratch and swaps them in only at its end, so that a
/// throw leaves everything as it was.
class PairEventsState {
public:
    void update(std::span<const Pair> pairs, std::span<const BoxId> replaced) {
        next_.assign(pairs);  // checks a < b
        scratch_.candidates.clear();
        scratch_.ended.clear();
        scratch_.renamed.clear();
        if (everything_replaced_) {
            // Every previous pair ends, every pair begins, even one with the same two names.
            if (previous_.is_packed) {
                for (const PackedPair pair : previous_.packed) scratch_.ended.push_back(unpacked(pair));
            } else {
                scratch_.ended.assign(previous_.wide.begin(), previous_.wide.end());
            }
            scratch_.candidates.assign(pairs.begin(), pairs.end());
        } else {
            std::optional<BodyFates> fates;
            if (!calls_.empty() || !replaced.empty()) fates.emplace(calls_, replaced);
            const BodyFates* followed = fates && !fates->empty() ? &*fates : nullptr;
            diff_partitions(followed);
        }
        settle_candidates();
        sort_pairs_fast(scratch_.ended, sort_buffer_);

        // Nothing below throws.
        std::swap(previous_, next_);
        begun_.swap(scratch_.candidates);
        ended_.swap(scratch_.ended);
        calls_.clear();
        everything_replaced_ = false;
    }

    void record(const BodyCall& call) { calls_.push_back(call); }
    void replace_all() noexcept { everything_replaced_ = true; }

    [[nodiscard]] std::span<const Pair> begun() const noexcept { return begun_; }
    [[nodiscard]] std::span<const Pair> ended() const noexcept { return ended_; }
    [[nodiscard]] std::size_t size() const noexcept { return previous_.size(); }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return sizeof(*this) + previous_.bytes_held() + next_.bytes_held() + scratch_.bytes_held() +
               (begun_.capacity() + ended_.capacity() + sort_buffer_.capacity()) * sizeof(Pair) +
               calls_.capacity() * sizeof(BodyCall);
    }

private:
    /// Each partition of the coarser of the two lists' layouts against the same hash range of
    /// the other: a range of whole partitions, contiguous in the layout.
    void diff_partitions(const BodyFates* fates) {
        const auto run = [&](const auto& previous_pairs, const auto& next_pairs) {
            const std::span previous(previous_pairs);
            const std::span next(next_pairs);
            const int unit_bits = std::min(previous_.bits, next_.bits);
            const std::size_t units = std::size_t{1} << unit_bits;
            const std::size_t previous_per_unit = std::size_t{1} << (previous_.bits - unit_bits);
            const std::size_t next_per_unit = std::size_t{1} << (next_.bits - unit_bits);
            for (std::size_t u = 0; u < units; ++u) {
                const std::size_t p0 = previous_.offsets[u * previous_per_unit];
                const std::size_t p1 = previous_.offsets[(u + 1) * previous_per_unit];
                const std::size_t n0 = next_.offsets[u * next_per_unit];
                const std::size_t n1 = next_.offsets[(u + 1) * next_per_unit];
                diff_partition(previous.subspan(p0, p1 - p0), next.subspan(n0, n1 - n0), unit_bits, fates, scratch_);
            }
        };
        if (previous_.is_packed) {
            if (next_.is_packed) {
                run(std::as_const(previous_.packed), std::as_const(next_.packed));
            } else {
                run(std::as_const(previous_.packed), std::as_const(next_.wide));
            }
        } else if (next_.is_packed) {
            run(std::as_const(previous_.wide), std::as_const(next_.packed));
        } else {
            run(std::as_const(previous_.wide), std::as_const(next_.wide));
        }
    }

    /// The candidates that are not renamed previous pairs begin; the renamed pairs not found
    /// among them ended, under their previous names. Sorting the candidates also finds a new pair
    /// listed twice: the two copies end up side by side.
    void settle_candidates() {
        auto& candidates = scratch_.candidates;
        sort_pairs_fast(candidates, sort_buffer_);
        const auto repeat = std::adjacent_find(candidates.begin(), candidates.end());
        if (repeat != candidates.end()) throw_repeated_pair(*repeat);
        auto& renamed = scratch_.renamed;
        if (renamed.empty()) return;
        std::sort(renamed.begin(), renamed.end(),
                  [](const RenamedPair& x, const RenamedPair& y) { return x.now < y.now; });
        std::size_t kept = 0;
        std::size_t r = 0;
        for (const Pair& pair : candidates) {
            while (r < renamed.size() && renamed[r].now < pair) scratch_.ended.push_back(renamed[r++].before);
            if (r < renamed.size() && renamed[r].now == pair) {
                ++r;  // the renamed pair goes on
            } else {
                candidates[kept++] = pair;
            }
        }
        for (; r < renamed.size(); ++r) scratch_.ended.push_back(renamed[r].before);
        candidates.resize(kept);
    }

    PairPartitions previous_;
    PairPartitions next_;
    DiffScratch scratch_;
    std::vector<Pair> begun_;
    std::vector<Pair> ended_;
    std::vector<BodyCall> calls_;
    std::vector<Pair> sort_buffer_;
    bool everything_replaced_ = false;
};

}  // namespace detail

PairEvents::PairEvents() : state_(std::make_unique<detail::PairEventsState>()) {}
PairEvents::~PairEvents() = default;
PairEvents::PairEvents(PairEvents&&) noexcept = default;
PairEvents& PairEvents::operator=(PairEvents&&) noexcept = default;

detail::PairEventsState& PairEvents::state() {
    if (!state_) state_ = std::make_unique<detail::PairEventsState>();
    return *state_;
}

void PairEvents::update(std::span<const Pair> pairs) { state().update(pairs, {}); }

void PairEvents::update(std::span<const Pair> pairs, std::span<const BoxId> replaced) {
    state().update(pairs, replaced);
}

void PairEvents::replace(BoxId name) { state().record({name, 0, false}); }

void PairEvents::replace_all() { state().replace_all(); }

void PairEvents::swap_remove(BoxId removed, BoxId last) {
    if (removed > last) {
        throw ArgumentError("PairEvents::swap_remove: removed index " + std::to_string(removed) +
                            " is past the last index " + std::to_string(last));
    }
    state().record({removed, last, true});
}

std::span<const Pair> PairEvents::begun() const noexcept { return state_ ? state_->begun() : std::span<const Pair>(); }

std::span<const Pair> PairEvents::ended() const noexcept { return state_ ? state_->ended() : std::span<const Pair>(); }

std::size_t PairEvents::size() const noexcept { return state_ ? state_->size() : 0; }

void PairEvents::clear() { state_ = std::make_unique<detail::PairEventsState>(); }

std::size_t PairEvents::bytes_held() const noexcept { return state_ ? state_->bytes_held() : 0; }

}  // namespace smb
