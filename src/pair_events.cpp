// SPDX-License-Identifier: MIT
#include "smb/pair_events.hpp"

#include <algorithm>
#include <cstddef>
#include <exception>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/pair_key_sort.hpp"
#include "core/thread_team.hpp"
#include "events/body_fates.hpp"
#include "events/pair_partitions.hpp"
#include "events/partition_diff.hpp"

namespace smb {

namespace detail {

/// The previous list, hashed into partitions; the calls made since; the last events. An update
/// builds the next list and the events in scratch and swaps them in only at its end, so that a
/// throw leaves everything as it was.
class PairEventsState {
public:
    explicit PairEventsState(unsigned threads) : threads_(threads) {}

    [[nodiscard]] unsigned threads() const noexcept { return threads_; }

    void update(std::span<const Pair> pairs, std::span<const BoxId> replaced) {
        const int threads = thread_count(DetectionSettings{.threads = threads_});
        const bool compare = !everything_replaced_ && previous_.size() != 0;
        std::optional<BodyFates> fates;
        if (compare && (!calls_.empty() || !replaced.empty())) fates.emplace(calls_, replaced);
        const BodyFates* followed = fates && !fates->empty() ? &*fates : nullptr;
        watched_.resize(static_cast<std::size_t>(threads));
        for (auto& watched : watched_) watched.clear();
        if (followed != nullptr) {
            // The pairs that name a body with a fate, gathered while the layout has them at hand.
            next_.assign(pairs, threads, [&](const Pair& pair, int thread) {
                if (followed->may_touch(pair)) watched_[static_cast<std::size_t>(thread)].push_back(pair);
            });
        } else {
            next_.assign(pairs, threads);  // checks a < b
        }
        scratch_.candidates.clear();
        scratch_.ended.clear();
        scratch_.renamed.clear();
        if (!compare) {
            // Nothing to compare: every previous pair ends, every pair begins, even one with the
            // same two names.
            previous_.for_each([&](const auto& pair) { scratch_.ended.push_back(unpacked(pair)); });
            scratch_.candidates.assign(pairs.begin(), pairs.end());
        } else {
            diff_partitions(followed, threads);
        }
        settle_candidates(followed);
        sort_pairs_fast(scratch_.ended, sort_scratch_);

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
               (begun_.capacity() + ended_.capacity()) * sizeof(Pair) + sort_scratch_.bytes_held() +
               calls_.capacity() * sizeof(BodyCall) + watched_bytes() +
               own_.bytes_held([](const DiffScratch& scratch) { return scratch.bytes_held(); });
    }

private:
    [[nodiscard]] std::size_t watched_bytes() const noexcept {
        std::size_t bytes = watched_.capacity() * sizeof(std::vector<Pair>);
        for (const auto& watched : watched_) bytes += watched.capacity() * sizeof(Pair);
        return bytes;
    }

    /// Each partition of the coarser of the two lists' layouts against the same hash range of
    /// the other: a range of whole partitions, contiguous in the layout. On several threads,
    /// each with its own scratch, merged after; the order of the events does not matter before
    /// they are sorted. A repeated pair is reported from the first partition that found one.
    void diff_partitions(const BodyFates* fates, int threads) {
        const int unit_bits = std::min(previous_.bits, next_.bits);
        const auto units = static_cast<std::ptrdiff_t>(std::size_t{1} << unit_bits);
        const int team = std::max(1, std::min<int>(threads, static_cast<int>(units / 16)));
        own_.resize(team);
        for (DiffScratch& scratch : own_) {
            scratch.candidates.clear();
            scratch.ended.clear();
            scratch.renamed.clear();
        }
        std::vector<std::ptrdiff_t> failed_unit(static_cast<std::size_t>(team), units);
        std::vector<std::exception_ptr> failure(static_cast<std::size_t>(team));
        const auto run = [&](const auto& previous_pairs, const auto& next_pairs) {
            using PreviousPair = typename std::remove_cvref_t<decltype(previous_pairs)>::value_type;
            using NextPair = typename std::remove_cvref_t<decltype(next_pairs)>::value_type;
#pragma omp parallel for num_threads(team) schedule(dynamic, 16) if (team > 1)
            for (std::ptrdiff_t unit = 0; unit < units; ++unit) {
                const auto u = static_cast<std::size_t>(unit);
                const auto t = static_cast<std::size_t>(this_thread());
                if (failed_unit[t] < unit) continue;
                DiffScratch& scratch = own_[t];
                try {
                    diff_partition(previous_.unit<PreviousPair>(u, unit_bits, scratch.previous_unit),
                                   next_.unit<NextPair>(u, unit_bits, scratch.current_unit), unit_bits, fates, scratch);
                } catch (...) {
                    failed_unit[t] = unit;
                    failure[t] = std::current_exception();
                }
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
        const auto first = std::min_element(failed_unit.begin(), failed_unit.end());
        if (*first != units) std::rethrow_exception(failure[static_cast<std::size_t>(first - failed_unit.begin())]);
        // A unit gathered whole (one list of few partitions against one of many) is rare; its
        // room is not kept.
        constexpr std::size_t kKeptUnit = std::size_t{1} << 16;
        for (DiffScratch& scratch : own_) {
            if (scratch.previous_unit.capacity() > kKeptUnit) std::vector<PackedPair>().swap(scratch.previous_unit);
            if (scratch.current_unit.capacity() > kKeptUnit) std::vector<PackedPair>().swap(scratch.current_unit);
        }
        // One thread's scratch becomes the whole; the others are appended to it.
        std::swap(scratch_.candidates, own_[0].candidates);
        std::swap(scratch_.ended, own_[0].ended);
        std::swap(scratch_.renamed, own_[0].renamed);
        for (std::size_t t = 1; t < own_.size(); ++t) {
            append(scratch_.candidates, own_[t].candidates);
            append(scratch_.ended, own_[t].ended);
            append(scratch_.renamed, own_[t].renamed);
        }
    }

    template <class T>
    static void append(std::vector<T>& to, const std::vector<T>& from) {
        to.insert(to.end(), from.begin(), from.end());
    }

    /// The candidates that are not renamed previous pairs begin; the renamed pairs not found
    /// among them ended, under their previous names. Sorting the candidates also finds a new pair
    /// listed twice: the two copies end up side by side.
    void settle_candidates(const BodyFates* fates) {
        auto& candidates = scratch_.candidates;
        sort_pairs_fast(candidates, sort_scratch_);
        const auto repeat = std::adjacent_find(candidates.begin(), candidates.end());
        if (repeat != candidates.end()) throw_repeated_pair(*repeat);
        if (fates != nullptr) settle_watched(*fates);
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

    /// A watched pair (one that names a body with a fate) not among the candidates met the
    /// previous pair of the same names in the comparison, which took them for one; the bodies
    /// under those names may differ. Where they do, the previous pair is followed to its
    /// bodies' names now and settled with the renamed ones, and the watched pair is a candidate.
    void settle_watched(const BodyFates& fates) {
        auto& watched = watched_[0];
        for (std::size_t t = 1; t < watched_.size(); ++t) append(watched, watched_[t]);
        sort_pairs_fast(watched, sort_scratch_);
        watched.erase(std::unique(watched.begin(), watched.end()), watched.end());  // a layout begun again
        auto& candidates = scratch_.candidates;
        const std::size_t candidate_count = candidates.size();
        auto from = candidates.begin();
        std::vector<Pair> met;
        for (const Pair& pair : watched) {
            from = std::lower_bound(from, candidates.begin() + static_cast<std::ptrdiff_t>(candidate_count), pair);
            if (from != candidates.end() && *from == pair) continue;  // not met: a candidate already
            Pair now = pair;
            const auto outcome = fates.follow(pair, now);
            if (outcome == BodyFates::Outcome::same) continue;  // the same bodies: it goes on
            if (outcome == BodyFates::Outcome::ended) {
                scratch_.ended.push_back(pair);
            } else {
                scratch_.renamed.push_back({now, pair});
            }
            met.push_back(pair);
        }
        if (met.empty()) return;
        const std::ptrdiff_t middle = static_cast<std::ptrdiff_t>(candidates.size());
        candidates.insert(candidates.end(), met.begin(), met.end());
        std::inplace_merge(candidates.begin(), candidates.begin() + middle, candidates.end());
    }

    unsigned threads_ = 1;
    std::vector<std::vector<Pair>> watched_;  // each layout thread's watched pairs
    PerThread<DiffScratch> own_;              // each thread's tables and findings in diff_partitions()
    PairPartitions previous_;
    PairPartitions next_;
    DiffScratch scratch_;
    std::vector<Pair> begun_;
    std::vector<Pair> ended_;
    std::vector<BodyCall> calls_;
    PairSortScratch sort_scratch_;
    bool everything_replaced_ = false;
};

}  // namespace detail

PairEvents::PairEvents(unsigned threads) : state_(std::make_unique<detail::PairEventsState>(threads)) {}
PairEvents::~PairEvents() = default;
PairEvents::PairEvents(PairEvents&&) noexcept = default;
PairEvents& PairEvents::operator=(PairEvents&&) noexcept = default;

detail::PairEventsState& PairEvents::state() {
    if (!state_) state_ = std::make_unique<detail::PairEventsState>(1);
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

void PairEvents::clear() { state_ = std::make_unique<detail::PairEventsState>(threads()); }

unsigned PairEvents::threads() const noexcept { return state_ ? state_->threads() : 1; }

std::size_t PairEvents::bytes_held() const noexcept { return state_ ? state_->bytes_held() : 0; }

}  // namespace smb
