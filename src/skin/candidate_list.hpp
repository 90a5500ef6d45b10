// SPDX-License-Identifier: MIT
#pragma once
// The skin list's candidates: the pairs of positions whose fat boxes overlap, each once, kept
// from one detection to the next, and the pass that tests them all on the held boxes. A dropped
// candidate becomes a tombstone, a pair of one position with itself, which the pass skips: the
// list is written only where it changes, and closed up once tombstones are a thirty-second of it.
// The candidates to drop are those of a vacant held box (empty_float_box(), held_box.hpp), which
// the pass's own compares tell apart: no per-candidate lookup of which boxes changed.
// The test of a pair of held boxes says whether they overlap, and whether they overlap by enough
// to prove that the input boxes they hold overlap too (held_sure_margin(), held_box.hpp).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "core/growth.hpp"
#include "core/id_index.hpp"
#include "core/ordered_rounds.hpp"
#include "core/pair_output.hpp"
#include "core/thread_team.hpp"
#include "core/tuning.hpp"
#include "cuts/float_lanes.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

#if defined(__GNUC__)
/// Held boxes `a` and `b` as four lanes of each corner (Dim <= 3): a lane past max[Dim-1] reads
/// the next box or the padding after the last, and the tests mask it off.
template <int Dim>
struct HeldLanes {
    static constexpr std::uint32_t all = (1U << Dim) - 1;
    FloatLanes<4>::Floats a_min, a_max, b_min, b_max;

    [[gnu::always_inline]] HeldLanes(const Box<float, Dim>* a, const Box<float, Dim>* b) noexcept {
        std::memcpy(&a_min, a->min.data(), sizeof a_min);
        std::memcpy(&a_max, a->max.data(), sizeof a_max);
        std::memcpy(&b_min, b->min.data(), sizeof b_min);
        std::memcpy(&b_max, b->max.data(), sizeof b_max);
    }

    /// 1 when every lane of `mask` within Dim is set, else 0. Arithmetic, not a comparison: GCC
    /// turns `== all ? 1 : 0` into a branch in the pass's loop, where half the candidates
    /// overlap and the predictor misses every other one.
    [[nodiscard, gnu::always_inline]] static std::uint32_t every_axis(FloatLanes<4>::Masks mask) noexcept {
        return ((lane_bits<4>(mask) & all) + 1U) >> Dim;
    }
    /// Bit 0 of candidate_bits(), and its bit 2: a or b is vacant, on the first axis neither
    /// reaches the other. One pair of compares for both.
    [[nodiscard, gnu::always_inline]] std::uint32_t hit_and_vacant() const noexcept {
        const FloatLanes<4>::Masks reach = a_min <= b_max;
        const FloatLanes<4>::Masks reached = b_min <= a_max;
        return every_axis(reach & reached) | ((~lane_bits<4>(reach | reached) & 1U) << 2);
    }
    [[nodiscard, gnu::always_inline]] std::uint32_t sure(float margin) const noexcept {
        return every_axis(((b_max - a_min) >= margin) & ((a_max - b_min) >= margin));
    }
};
#endif

/// What the pass over the candidates learns of held boxes `a` and `b`:
/// - bit 0 (kHitBit): they overlap;
/// - bit 1 (kSureBit, only `with_sure`): they overlap by at least `sure_margin` on every axis,
///   which proves that the input boxes overlap too;
/// - bit 2 (kVacantBit): a or b is vacant (empty_float_box(), held_box.hpp). Two boxes with
///   min <= max always reach each other on an axis from one side or the other (a.min <= b.max
///   or b.min <= a.max); a vacant box, from +infinity to -infinity, reaches nothing from either,
///   and overlaps nothing.
/// Four lanes at a time where GCC's vector extensions are at hand (HeldLanes), so that no branch
/// depends on the answer.
inline constexpr std::uint32_t kHitBit = 1;
inline constexpr std::uint32_t kSureBit = 2;
inline constexpr std::uint32_t kVacantBit = 4;
template <int Dim, bool with_sure>
[[nodiscard, gnu::always_inline]] inline std::uint32_t candidate_bits(const Box<float, Dim>* a,
                                                                      const Box<float, Dim>* b,
                                                                      float sure_margin) noexcept {
#if defined(__GNUC__)
    if constexpr (Dim <= 3) {
        const HeldLanes<Dim> lanes(a, b);
        if constexpr (with_sure) return lanes.hit_and_vacant() | (lanes.sure(sure_margin) << 1);
        return lanes.hit_and_vacant();
    }
#endif
    std::uint32_t hit_bits = 0;
    std::uint32_t sure_bits = 0;
    for (int k = 0; k < Dim; ++k) {
        const bool hit = a->min[k] <= b->max[k] && b->min[k] <= a->max[k];
        const bool sure = b->max[k] - a->min[k] >= sure_margin && a->max[k] - b->min[k] >= sure_margin;
        hit_bits |= static_cast<std::uint32_t>(hit) << k;
        sure_bits |= static_cast<std::uint32_t>(sure) << k;
    }
    const bool vacant = !(a->min[0] <= b->max[0]) && !(b->min[0] <= a->max[0]);
    std::uint32_t bits = ((hit_bits + 1U) >> Dim) | (static_cast<std::uint32_t>(vacant) << 2);
    if constexpr (with_sure) bits |= ((sure_bits + 1U) >> Dim) << 1;
    return bits;
}

/// Bits 0 and 1 of candidate_bits(): one pair tested on its own.
template <int Dim>
[[nodiscard, gnu::always_inline]] inline std::uint32_t overlap_bits(const Box<float, Dim>* a, const Box<float, Dim>* b,
                                                                    float sure_margin) noexcept {
    return candidate_bits<Dim, true>(a, b, sure_margin) & (kHitBit | kSureBit);
}

template <int Dim>
class CandidateList {
public:
    using Position = std::uint32_t;
    using Held = Box<float, Dim>;
    struct Candidate {
        Position a;
        Position b;
    };
    /// Thrown by the collector of a rebuild once the list would pass its cap.
    struct TooManyCandidates {};
    /// Rebuild: collects the pipeline's pairs of fat boxes (slots, turned into positions after).
    struct Collector {
        std::vector<Candidate>& candidates;
        std::size_t cap;
        void operator()(BoxId a, BoxId b) {
            if (candidates.size() >= cap) throw TooManyCandidates{};
            candidates.push_back(Candidate{static_cast<Position>(a), static_cast<Position>(b)});
        }
        void append(std::span<const Pair> pairs) {
            for (const Pair& pair : pairs) (*this)(pair.a, pair.b);
        }
    };

    /// An empty list, and a collector that fills it with up to `cap` pairs of slots.
    [[nodiscard]] Collector rebuild(std::size_t cap) {
        candidates_.clear();
        tombstones_ = 0;
        return Collector{candidates_, cap};
    }

    /// The rebuilt pairs of slots become pairs of positions.
    void renumber(std::span<const Position> position_of) {
        for (Candidate& candidate : candidates_) {
            candidate.a = position_of[candidate.a];
            candidate.b = position_of[candidate.b];
        }
        // The list grew by doubling while the pipeline reported: up to twice what it holds.
        // Kept with a sixteenth of room, as the arrays that follow N (growth.hpp).
        if (candidates_.capacity() > candidates_.size() + candidates_.size() / 8) {
            std::vector<Candidate> trimmed;
            trimmed.reserve(capacity_with_slack(candidates_.size(), false));
            trimmed.assign(candidates_.begin(), candidates_.end());
            candidates_.swap(trimmed);
        }
    }

    void add(Position p, Position q) {
        reserve_with_slack(candidates_, candidates_.size() + 1);  // not doubling the list
        candidates_.push_back(Candidate{p, q});
    }

    /// Candidates and tombstones.
    [[nodiscard]] std::size_t size() const noexcept { return candidates_.size(); }
    /// Candidates without the tombstones.
    [[nodiscard]] std::size_t live() const noexcept { return candidates_.size() - tombstones_; }
    /// The live candidates as pairs of names (name_of[position]), a < b, in the order of the list.
    void pairs_named(std::span<const Slot> name_of, std::vector<Pair>& out) const {
        out.clear();
        out.reserve(live());
        for (const Candidate& candidate : candidates_) {
            if (candidate.a == candidate.b) continue;  // a tombstone
            out.push_back(ordered_pair(BoxId{name_of[candidate.a]}, BoxId{name_of[candidate.b]}));
        }
    }

    /// What a pass reads: the held boxes by position (one more of padding, for candidate_bits()),
    /// those whose candidates are dropped in this detection vacant, the sure margin, the caller's index
    /// of each position, confirm(a, b, sure, retested), which says whether a pair the floats
    /// pass holds for the input too, counting in `retested` the pairs it tests again, and whether
    /// the held boxes are the input's own (`exact`: a held overlap is the pair, confirm is not asked).
    template <class Confirm, class Name>
    struct Pass {
        const Held* held;
        float sure_margin;
        std::span<const Name> name_of;  // the name each position's pairs are reported under
        const Confirm& confirm;
        bool exact;
    };

    /// Tests every candidate, after dropping those of vacant boxes when `dropping`,
    /// and reports the pairs in the order of the list, whatever the number of threads. Returns the
    /// pairs tested again on the input.
    template <class Confirm, class Name, class Report>
    std::size_t test(const Pass<Confirm, Name>& pass, bool dropping, int threads, Report& report) {
        const std::size_t count = candidates_.size();
        workers_.resize(threads);
        std::size_t retested = 0;
        if (threads == 1 || count < tuning::skin_parallel_from) {
            // Each pair straight to the report (into the caller's vector, where it is one): a block
            // of pairs appended after would write each pair twice.
            Block out;
            test_range(pass, 0, count, dropping, workers_[0], out, [&](BoxId a, BoxId b) { report(a, b); });
            retested += out.retested;
            tombstones_ += out.tombstones;
        } else {
            retested += test_in_rounds(pass, dropping, threads, report);
        }
        if (32 * tombstones_ > count) {
            std::erase_if(candidates_, [](const Candidate& candidate) { return candidate.a == candidate.b; });
            tombstones_ = 0;
        }
        return retested;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        std::size_t bytes = candidates_.capacity() * sizeof(Candidate);
        bytes += workers_.bytes_held(
            [](const Worker& worker) { return worker.hits.capacity() * sizeof(Candidate) + worker.sure.capacity(); });
        for (const Block& block : blocks_) bytes += block.pairs.capacity() * sizeof(Pair);
        return bytes;
    }

private:
    /// The pairs found in one block of candidates, and its counts.
    struct alignas(64) Block {
        std::vector<Pair> pairs;
        std::size_t retested = 0;
        std::size_t tombstones = 0;
    };
    /// One thread's buffers: a run of hits waiting to become pairs.
    struct Worker {
        std::vector<Candidate> hits;
        std::vector<std::uint8_t> sure;
    };

    /// Several threads: blocks of candidates in rounds, each block's pairs buffered, handed to
    /// the report in list order on the calling thread (ordered_rounds.hpp). After a throwing
    /// sink the blocks left are not tested; the list is rebuilt at the next detection anyway.
    template <class Confirm, class Name, class Report>
    std::size_t test_in_rounds(const Pass<Confirm, Name>& pass, bool dropping, int threads, Report& report) {
        const std::size_t count = candidates_.size();
        const std::size_t blocks = (count + tuning::skin_block_candidates - 1) / tuning::skin_block_candidates;
        const std::size_t round = 4 * static_cast<std::size_t>(threads);
        std::size_t retested = 0;
        run_in_ordered_rounds(
            threads, blocks, round, blocks_,
            [&](std::size_t item, Block& block) {
                block.pairs.clear();
                block.retested = 0;
                block.tombstones = 0;
                const std::size_t first = item * tuning::skin_block_candidates;
                test_range(pass, first, std::min(first + tuning::skin_block_candidates, count), dropping,
                           workers_.mine(), block,
                           [&block](BoxId a, BoxId b) { block.pairs.push_back(ordered_pair(a, b)); });
            },
            [&](std::size_t, Block& block) {
                retested += block.retested;
                tombstones_ += block.tombstones;
                report.append(block.pairs);
            });
        return retested;
    }

    /// Candidates [first, last): each pair to emit(name_a, name_b), the counts into `out`.
    template <class Confirm, class Name, class Emit>
    void test_range(const Pass<Confirm, Name>& pass, std::size_t first, std::size_t last, bool dropping, Worker& worker,
                    Block& out, Emit&& emit) {
        if (pass.exact)
            test_range_as<true>(pass, first, last, dropping, worker, out, emit);
        else
            test_range_as<false>(pass, first, last, dropping, worker, out, emit);
    }

    /// Branch-free over the candidates (about half of them overlap, which no predictor guesses).
    /// `exact`: the held boxes are the input's own, so no sure bit is kept and no pair confirmed.
    template <bool exact, class Confirm, class Name, class Emit>
    void test_range_as(const Pass<Confirm, Name>& pass, std::size_t first, std::size_t last, bool dropping,
                       Worker& worker, Block& out, Emit& emit) {
        constexpr std::size_t kRun = 2048;
        worker.hits.resize(kRun);
        worker.sure.resize(kRun);
        Candidate* candidates = candidates_.data();
        Candidate* hit_list = worker.hits.data();
        std::uint8_t* sure_list = worker.sure.data();
        const Held* held = pass.held;
        const float sure_margin = pass.sure_margin;
        std::size_t hits = 0;
        for (std::size_t i = first; i < last; ++i) {
            const Candidate candidate = candidates[i];
            const Held* a = held + candidate.a;
            const Held* b = held + candidate.b;
            const std::uint32_t bits = candidate_bits<Dim, !exact>(a, b, sure_margin);
            // A vacant box overlaps nothing, so its candidates never hit: only the drop is left.
            if (dropping && (bits & kVacantBit) != 0 && candidate.a != candidate.b) [[unlikely]] {
                candidates[i] = Candidate{candidate.a, candidate.a};
                ++out.tombstones;
            }
            hit_list[hits] = candidate;
            if constexpr (!exact) sure_list[hits] = static_cast<std::uint8_t>((bits & kSureBit) >> 1);
            hits += bits & kHitBit;
            if (hits == kRun) {
                pairs_of_hits<exact>(pass, hits, worker, out, emit);
                hits = 0;
            }
        }
        pairs_of_hits<exact>(pass, hits, worker, out, emit);
    }

    /// The pairs of a run of hits, each confirmed on the input where the floats cannot settle it
    /// (never where they are `exact`).
    template <bool exact, class Confirm, class Name, class Emit>
    static void pairs_of_hits(const Pass<Confirm, Name>& pass, std::size_t hits, const Worker& worker, Block& out,
                              Emit& emit) {
        const Name* name_of = pass.name_of.data();
        for (std::size_t i = 0; i < hits; ++i) {
            const Candidate hit = worker.hits[i];
            if (hit.a == hit.b) continue;  // a tombstone
            if constexpr (!exact) {
                if (!pass.confirm(hit.a, hit.b, worker.sure[i] != 0, out.retested)) continue;
            }
            emit(BoxId{name_of[hit.a]}, BoxId{name_of[hit.b]});
        }
    }

    std::vector<Candidate> candidates_;  // pairs of positions whose fat boxes overlap, each once; and tombstones
    std::size_t tombstones_ = 0;         // candidates dropped in place (a pair of a position with itself)
    PerThread<Worker> workers_;
    std::vector<Block> blocks_;  // two rounds of blocks of candidates (several threads)
};

}  // namespace smb::detail
