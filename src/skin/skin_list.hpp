#pragma once
// The skin list (a Verlet list, in the words of molecular dynamics and DEM codes): each box is
// held inside a fat box, grown by the skin on every side, and the pairs of fat boxes that overlap
// are kept as candidates from one detection to the next. While every box stays inside its fat
// box, the overlapping pairs are among the candidates, so a detection is one pass that checks
// each box against its fat box and one exact test per candidate: no cut, no regrouping, no sort.
//
// A box that left its fat box (or is new, or came back after the array shrank) gets a new fat
// box, loses its candidates, and finds new ones: the boxes whose fat boxes overlap its new one,
// through the cells of the last rebuild (PersistentCutPipeline::for_each_held_overlapping) for
// the boxes that have kept their fat box since, and by a direct test against the few that have
// not (the moved list). When that list grows past a share of N, everything is rebuilt: the
// persistent-cut pipeline detects the pairs of the fat boxes, and those are the new candidates.
//
// Why no pair is lost: every box lies inside its fat box (checked each detection, on the held
// floats, whose rounding never reverses an order: held_box.hpp), so two boxes that overlap have
// fat boxes that overlap, and every such pair is a candidate; each candidate is kept once.
//
// Positions: the boxes are held in the cell order the rebuild left (slot_of_), so that a
// candidate's two boxes lie close together in held_ and the pass over the candidates reads memory
// almost in order. The caller's array is read once per detection, in that order.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include "core/growth.hpp"
#include "core/held_box.hpp"
#include "core/id_index.hpp"
#include "core/ordered_rounds.hpp"
#include "cuts/persistent_cut_pipeline.hpp"
#include "core/prefetch.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

#ifdef _OPENMP
#include <omp.h>  // omp_get_max_threads
#endif

namespace smb::detail {

template <std::floating_point Input, int Dim>
class SkinList {
public:
    using Held = Box<float, Dim>;

    /// Reports every overlapping pair of `input` (box i under id i) to report(i, j). `origin`:
    /// where held coordinates start (held_box.hpp; zero for float input). Returns false, having
    /// reported nothing and released its memory, when the fat boxes make more candidates than
    /// it will hold (about 32 per box), when a quarter of the boxes left their fat boxes since
    /// the last detection (a skin far too thin for the motion), or after the candidates were
    /// rebuilt twice running before serving kShortLife detections (a rebuild costs more than a
    /// detection without a skin): the caller then detects without a skin.
    template <class Report>
    bool detect(std::span<const Box<Input, Dim>> input, const std::array<Input, Dim>& origin,
                const std::array<Input, Dim>& scene_lo, const std::array<Input, Dim>& scene_hi, double skin,
                const WorldSettings& settings, Report& report, DetectStats& stats) {
        input_ = input;
#ifdef _OPENMP
        threads_ = std::max(1, settings.threads == 0 ? omp_get_max_threads() : static_cast<int>(settings.threads));
#endif
        sure_margin_ = kExact ? 0.0F : held_sure_margin<Input, Dim>(origin, scene_lo, scene_hi);
        retested_ = 0;
        refreshed_ = 0;
        rebuilt_ = false;
        const std::size_t n = input.size();
        if (exhausted_) {
            clear();
            return false;
        }
        const bool stale = !built_ || origin != origin_ || skin != skin_ || 4 * n > 5 * rebuilt_boxes_ ||
                           5 * n < 4 * rebuilt_boxes_;
        try {
            const Outcome outcome = stale ? Outcome::rebuild : step(report, stats);
            if (outcome == Outcome::hopeless) {
                clear();
                return false;
            }
            if (outcome == Outcome::rebuild) {
                origin_ = origin;
                skin_ = skin;
                if (!rebuild(settings, stats)) return false;
                test_candidates(report, false);
            }
        } catch (...) {
            // A sink that threw (or a pair limit) may have left the candidates half compacted:
            // the next detection starts from a rebuild.
            built_ = false;
            throw;
        }
        if (candidates_.size() > candidate_cap(n)) built_ = false;  // let the next rebuild judge
        stats.skin_candidates = candidates_.size() - tombstones_;
        stats.skin_refreshed = refreshed_;
        stats.skin_rebuilt = rebuilt_;
        count_life();
        return true;
    }

    /// Pairs the held floats could not settle, tested again on the input, in the last detection.
    [[nodiscard]] std::size_t retested() const noexcept { return retested_; }

    void clear() { *this = SkinList(); }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return cells_.bytes_held() + (fat_.capacity() + held_.capacity()) * sizeof(Held) +
               (slot_of_.capacity() + position_of_.capacity() + moved_.capacity() + fresh_.capacity()) *
                   sizeof(std::uint32_t) +
               state_.capacity() + gone_.capacity() * sizeof(Position) + dirty_.capacity() * sizeof(std::uint64_t) +
               candidates_.capacity() * sizeof(Candidate) + scratch_bytes();
    }

private:
    using Clock = std::chrono::steady_clock;
    /// Below this many positions or candidates one thread does the pass alone.
    static constexpr std::size_t kParallelFrom = std::size_t{1} << 15;
    static constexpr std::size_t kBlockCandidates = std::size_t{1} << 15;

    [[nodiscard]] std::size_t scratch_bytes() const noexcept {
        std::size_t bytes = 0;
        for (const Scan& scan : scans_) bytes += (scan.fresh.capacity() + scan.gone.capacity()) * sizeof(Position);
        for (const Worker& worker : workers_)
            bytes += worker.hits.capacity() * sizeof(Candidate) + worker.sure.capacity();
        for (const Block& block : blocks_) bytes += block.pairs.capacity() * sizeof(Pair);
        bytes += serial_.pairs.capacity() * sizeof(Pair);
        return bytes;
    }
    using Position = std::uint32_t;
    struct Candidate {
        Position a;
        Position b;
    };
    /// Rebuild: collects the pipeline's pairs of fat boxes (slots, turned into positions after).
    struct TooManyCandidates {};
    struct CandidateCollector {
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

    // Per position.
    static constexpr std::uint8_t kMoved = 1;  // fat box changed since the rebuild (or new): not in the cells
    static constexpr std::uint8_t kFresh = 2;  // fat box changed in this detection
    static constexpr std::uint8_t kGone = 4;   // its slot is past the caller's array
    static constexpr std::uint8_t kDone = 8;   // fresh, and its new candidates are found already

    static constexpr bool kExact = std::same_as<Input, float>;  // held boxes are the input's own

    /// A life: the detections the candidates served between two rebuilds. Two short ones
    /// running, and the next detect() steps aside (after this one has reported its pairs).
    static constexpr std::size_t kShortLife = 4;
    void count_life() {
        if (!rebuilt_) {
            ++kept_since_rebuild_;
            return;
        }
        if (kept_since_rebuild_ >= kShortLife) {
            short_lives_ = 0;
        } else if (++short_lives_ >= 2) {
            clear();
            exhausted_ = true;
            return;
        }
        kept_since_rebuild_ = 0;
    }

    [[nodiscard]] static std::size_t candidate_cap(std::size_t n) noexcept { return 32 * n + (std::size_t{1} << 20); }
    /// The moved list is tested against every fresh box: past this length a rebuild is cheaper.
    [[nodiscard]] static std::size_t moved_limit(std::size_t n) noexcept { return std::max<std::size_t>(64, n / 64); }

    [[nodiscard]] Held fattened(const Held& held) const noexcept {
        Held fat;
        for (int k = 0; k < Dim; ++k) {
            fat.min[k] = float_below(static_cast<double>(held.min[k]) - skin_);
            fat.max[k] = float_above(static_cast<double>(held.max[k]) + skin_);
        }
        return fat;
    }

    [[nodiscard]] static bool inside(const Held& box, const Held& fat) noexcept {
        bool in = true;
        for (int k = 0; k < Dim; ++k) in &= fat.min[k] <= box.min[k] && box.max[k] <= fat.max[k];
        return in;
    }

    /// The pipeline's pairs of fat boxes become the candidates; positions follow its new order.
    bool rebuild(const WorldSettings& settings, DetectStats& stats) {
        rebuilt_ = true;
        const std::size_t n = input_.size();
        // held_ serves as the fat boxes by slot until the positions are known.
        resize_with_slack(held_, n + 1);  // and one box of padding for overlap_bit()
        for (std::size_t slot = 0; slot < n; ++slot) held_[slot] = fattened(held_box<Input, Dim>(input_[slot], origin_));
        candidates_.clear();
        tombstones_ = 0;
        cells_.forget_slots_from(n);
        CandidateCollector collect{candidates_, candidate_cap(n)};
        try {
            cells_.detect(std::span<const Held>(held_.data(), n), {}, settings, collect, stats);
        } catch (const TooManyCandidates&) {
            clear();
            return false;
        }
        const std::span<const Slot> order = cells_.order();
        slot_of_.assign(order.begin(), order.end());
        resize_with_slack(position_of_, n);
        resize_with_slack(fat_, n);
        for (std::size_t p = 0; p < n; ++p) {
            position_of_[slot_of_[p]] = static_cast<Position>(p);
            fat_[p] = held_[slot_of_[p]];
        }
        for (Candidate& candidate : candidates_) {
            candidate.a = position_of_[candidate.a];
            candidate.b = position_of_[candidate.b];
        }
        // The list grew by doubling while the pipeline reported: up to twice what it holds.
        // Kept with a sixteenth of room, as the arrays that follow N (growth.hpp).
        if (candidates_.capacity() > candidates_.size() + candidates_.size() / 8) {
            std::vector<Candidate> trimmed;
            trimmed.reserve(candidates_.size() + candidates_.size() / 16);
            trimmed.assign(candidates_.begin(), candidates_.end());
            candidates_.swap(trimmed);
        }
        gather_held();
        state_.assign(n, 0);
        dirty_.assign((n + 63) / 64, 0);
        moved_.clear();
        fresh_.clear();
        rebuilt_boxes_ = n;
        built_ = true;
        return true;
    }

    /// held_[p] from the caller's box at slot_of_[p], for every position (right after a
    /// rebuild, when every slot is in the array).
    void gather_held() {
        const std::size_t count = slot_of_.size();
        constexpr std::size_t ahead = 32;
        for (std::size_t p = 0; p < count; ++p) {
            if (p + ahead < count) prefetch_whole(&input_[slot_of_[p + ahead]]);
            held_[p] = held_box<Input, Dim>(input_[slot_of_[p]], origin_);
        }
    }

    enum class Outcome { kept, rebuild, hopeless };

    /// One detection on the kept candidates; before reporting anything, rebuild when the moved
    /// list would outgrow its limit, hopeless when a quarter of the boxes left their fat boxes.
    template <class Report>
    Outcome step(Report& report, DetectStats& stats) {
        const auto start = Clock::now();
        const std::size_t n = input_.size();
        const std::size_t known = position_of_.size();
        // Each thread scans a contiguous share of the positions; their lists, joined in thread
        // order, are the lists of one scan.
        if (scans_.size() != static_cast<std::size_t>(threads_)) scans_.resize(static_cast<std::size_t>(threads_));
        const std::size_t count = slot_of_.size();
#pragma omp parallel num_threads(threads_) if (threads_ > 1 && count >= kParallelFrom)
        {
            const auto thread = static_cast<std::size_t>(this_thread());
            const std::size_t shares = static_cast<std::size_t>(team_size());
            scan(count * thread / shares, count * (thread + 1) / shares, scans_[thread]);
        }
        fresh_.clear();
        gone_.clear();
        std::size_t newly_moved = 0;
        for (Scan& scan : scans_) {
            fresh_.insert(fresh_.end(), scan.fresh.begin(), scan.fresh.end());
            gone_.insert(gone_.end(), scan.gone.begin(), scan.gone.end());
            newly_moved += scan.newly_moved;
            scan.fresh.clear();
            scan.gone.clear();
            scan.newly_moved = 0;
        }
        // A quarter of the boxes out of their skin in one detection: the skin is far too thin
        // for the motion, and a rebuild costs more than a detection without it.
        if (4 * fresh_.size() > n) return Outcome::hopeless;
        if (n > known) newly_moved += n - known;
        if (moved_.size() + newly_moved > moved_limit(n)) return Outcome::rebuild;
        if (n > known) {
            // push_back would double each array when it is full: a sixteenth of room instead.
            const std::size_t positions = slot_of_.size() + (n - known);
            reserve_with_slack(slot_of_, positions);
            reserve_with_slack(position_of_, n);
            reserve_with_slack(held_, positions + 1);
            reserve_with_slack(fat_, positions);
            reserve_with_slack(state_, positions);
        }
        for (std::size_t slot = known; slot < n; ++slot) {
            const auto p = static_cast<Position>(slot_of_.size());
            slot_of_.push_back(static_cast<Slot>(slot));
            position_of_.push_back(p);
            held_.back() = held_box<Input, Dim>(input_[slot], origin_);
            held_.push_back(Held{});  // the padding
            fat_.push_back(Held{});
            state_.push_back(0);
            fresh_.push_back(p);
        }
        for (const Position p : fresh_) {
            fat_[p] = fattened(held_[p]);
            std::uint8_t& state = state_[p];
            state &= static_cast<std::uint8_t>(~kGone);
            if ((state & kMoved) == 0) moved_.push_back(p);
            state |= kMoved | kFresh;
        }
        refreshed_ = fresh_.size();
        const bool newly_gone = !gone_.empty();
        resize_with_slack(dirty_, (slot_of_.size() + 63) / 64);
        for (const Position p : fresh_) dirty_[p >> 6] |= std::uint64_t{1} << (p & 63);
        for (const Position p : gone_) dirty_[p >> 6] |= std::uint64_t{1} << (p & 63);
        stats.update_seconds += std::chrono::duration<double>(Clock::now() - start).count();

        const auto check_start = Clock::now();
        test_candidates(report, !fresh_.empty() || newly_gone);
        for (const Position p : fresh_) find_candidates_of(p, report);
        for (const Position p : fresh_) state_[p] &= static_cast<std::uint8_t>(~(kFresh | kDone));
        for (const Position p : fresh_) dirty_[p >> 6] = 0;
        for (const Position p : gone_) dirty_[p >> 6] = 0;
        stats.check_seconds = std::chrono::duration<double>(Clock::now() - check_start).count();
        return Outcome::kept;
    }

    /// What one thread's share of the containment check found.
    struct alignas(64) Scan {
        std::vector<Position> fresh;  // boxes out of their fat box, or back in the array
        std::vector<Position> gone;   // positions whose slot just left the array
        std::size_t newly_moved = 0;  // of the fresh ones, those not moved since the rebuild
    };

    /// Positions [first, last): the caller's boxes as held floats into held_, and each checked
    /// against its fat box.
    void scan(std::size_t first, std::size_t last, Scan& found) {
        const std::size_t n = input_.size();
        constexpr std::size_t ahead = 32;
        for (std::size_t p = first; p < last; ++p) {
            const Slot slot = slot_of_[p];
            std::uint8_t& state = state_[p];
            if (slot >= n) {
                if ((state & kGone) == 0) {
                    state |= kGone;
                    found.gone.push_back(static_cast<Position>(p));
                }
                continue;
            }
            if (p + ahead < last && slot_of_[p + ahead] < n) prefetch_whole(&input_[slot_of_[p + ahead]]);
            const Held held = held_box<Input, Dim>(input_[slot], origin_);
            // Read before held_[p] is written: the two arrays start alike modulo 4 KiB (each its
            // own mapping), so the load after the store waited on it (4K aliasing; the scan took
            // 13.8 ms instead of 12.3 at 1M, docs/performance.md).
            const Held fat = fat_[p];
            held_[p] = held;
            if ((state & kGone) != 0 || !inside(held, fat)) {
                found.fresh.push_back(static_cast<Position>(p));
                found.newly_moved += (state & kMoved) == 0 ? 1U : 0U;
            }
        }
    }

    /// Held boxes at a and b overlap: true when their input boxes do too. `sure`: the floats
    /// proved it (overlap_bits()); otherwise the input is asked, and `retested` counts it.
    [[nodiscard]] bool confirmed(Position a, Position b, bool sure, std::size_t& retested) const {
        if (kExact || sure) return true;
        ++retested;
        return overlaps(input_[slot_of_[a]], input_[slot_of_[b]]);
    }

    template <class Report>
    void test(Position a, Position b, Report& report) {
        const std::uint32_t bits = overlap_bits(&held_[a], &held_[b]);
        if ((bits & 1U) != 0 && confirmed(a, b, (bits & 2U) != 0, retested_))
            report(BoxId{slot_of_[a]}, BoxId{slot_of_[b]});
    }

    /// Tests every candidate, after dropping those of boxes marked in dirty_ when `dropping`,
    /// and reports the pairs in the order of the list, whatever the number of threads. A dropped
    /// candidate becomes a tombstone, a pair of one position with itself, which the report
    /// skips: the list is written only where it changes, and closed up once tombstones are a
    /// thirty-second of it.
    template <class Report>
    void test_candidates(Report& report, bool dropping) {
        const std::size_t count = candidates_.size();
        if (threads_ == 1 || count < kParallelFrom) {
            if (workers_.empty()) workers_.resize(1);
            Block& out = serial_;
            out.pairs.clear();
            out.retested = 0;
            out.tombstones = 0;
            test_range(0, count, dropping, workers_[0], out, [&] {
                report.append(out.pairs);
                out.pairs.clear();
            });
            report.append(out.pairs);
            retested_ += out.retested;
            tombstones_ += out.tombstones;
        } else {
            test_in_rounds(report, dropping);
        }
        if (32 * tombstones_ > count) {
            std::erase_if(candidates_, [](const Candidate& candidate) { return candidate.a == candidate.b; });
            tombstones_ = 0;
        }
    }

    /// The pairs found in one block of candidates, and its counts.
    struct alignas(64) Block {
        std::vector<Pair> pairs;
        std::size_t retested = 0;
        std::size_t tombstones = 0;
    };
    /// One thread's buffers: a run of hits waiting to become pairs.
    struct alignas(64) Worker {
        std::vector<Candidate> hits;
        std::vector<std::uint8_t> sure;
    };

    /// Several threads: blocks of candidates in rounds, each block's pairs buffered, handed to
    /// the report in list order on the calling thread (ordered_rounds.hpp). After a throwing
    /// sink the blocks left are not tested; the list is rebuilt at the next detection anyway.
    template <class Report>
    void test_in_rounds(Report& report, bool dropping) {
        const std::size_t count = candidates_.size();
        const auto threads = static_cast<std::size_t>(threads_);
        if (workers_.size() < threads) workers_.resize(threads);
        const std::size_t blocks = (count + kBlockCandidates - 1) / kBlockCandidates;
        const std::size_t round = 4 * threads;
        run_in_ordered_rounds(
            threads_, blocks, round, blocks_,
            [&](std::size_t item, Block& block) {
                block.pairs.clear();
                block.retested = 0;
                block.tombstones = 0;
                const std::size_t first = item * kBlockCandidates;
                test_range(first, std::min(first + kBlockCandidates, count), dropping,
                           workers_[static_cast<std::size_t>(this_thread())], block, [] {});
            },
            [&](std::size_t, Block& block) {
                retested_ += block.retested;
                tombstones_ += block.tombstones;
                report.append(block.pairs);
            });
    }

    /// Candidates [first, last) into `out`; flush() is called whenever a run of hits has become
    /// pairs. Branch-free over the candidates (about half of them overlap, which no predictor
    /// guesses).
    template <class Flush>
    void test_range(std::size_t first, std::size_t last, bool dropping, Worker& worker, Block& out, Flush&& flush) {
        constexpr std::size_t kRun = 2048;
        worker.hits.resize(kRun);
        worker.sure.resize(kRun);
        Candidate* candidates = candidates_.data();
        const Held* held = held_.data();
        const std::uint64_t* dirty = dirty_.data();
        std::size_t hits = 0;
        for (std::size_t i = first; i < last; ++i) {
            const Candidate candidate = candidates[i];
            std::uint32_t keep = 1;
            if (dropping) {
                keep = static_cast<std::uint32_t>(~((dirty[candidate.a >> 6] >> (candidate.a & 63)) |
                                                    (dirty[candidate.b >> 6] >> (candidate.b & 63))) & 1U);
                if (keep == 0 && candidate.a != candidate.b) {
                    candidates[i] = Candidate{candidate.a, candidate.a};
                    ++out.tombstones;
                }
            }
            const std::uint32_t bits = overlap_bits(held + candidate.a, held + candidate.b);
            worker.hits[hits] = candidate;
            worker.sure[hits] = static_cast<std::uint8_t>(bits >> 1);
            hits += keep & bits;
            if (hits == kRun) {
                pairs_of_hits(hits, worker, out);
                flush();
                hits = 0;
            }
        }
        pairs_of_hits(hits, worker, out);
    }

    /// The pairs of a run of hits, each confirmed on the input where the floats cannot settle it.
    void pairs_of_hits(std::size_t hits, const Worker& worker, Block& out) const {
        for (std::size_t i = 0; i < hits; ++i) {
            const Candidate hit = worker.hits[i];
            if (hit.a == hit.b) continue;  // a tombstone
            if (!confirmed(hit.a, hit.b, worker.sure[i] != 0, out.retested)) continue;
            const BoxId a = slot_of_[hit.a];
            const BoxId b = slot_of_[hit.b];
            out.pairs.push_back(a < b ? Pair{a, b} : Pair{b, a});
        }
    }

    /// Bit 0: held boxes `a` and `b` overlap; bit 1: they overlap by at least sure_margin_ on
    /// every axis, which proves that the input boxes overlap too (see detect()). Four lanes at a
    /// time where GCC's vector extensions are at hand (a lane past max[Dim-1] reads the next box
    /// or held_'s padding, and is masked off), so that no branch depends on the answer.
    [[nodiscard]] std::uint32_t overlap_bits(const Held* a, const Held* b) const noexcept {
        constexpr std::uint32_t all = (1U << Dim) - 1;
#if defined(__GNUC__)
        if constexpr (Dim <= 3) {
            using Lanes = FloatLanes<4>::Floats;
            Lanes a_min, a_max, b_min, b_max;
            std::memcpy(&a_min, a->min.data(), sizeof a_min);
            std::memcpy(&a_max, a->max.data(), sizeof a_max);
            std::memcpy(&b_min, b->min.data(), sizeof b_min);
            std::memcpy(&b_max, b->max.data(), sizeof b_max);
            const FloatLanes<4>::Masks hit = (a_min <= b_max) & (b_min <= a_max);
            const FloatLanes<4>::Masks sure = ((b_max - a_min) >= sure_margin_) & ((a_max - b_min) >= sure_margin_);
            const std::uint32_t hit_bits = lane_bits<4>(hit) & all;
            const std::uint32_t sure_bits = lane_bits<4>(sure) & all;
            return (hit_bits == all ? 1U : 0U) | (sure_bits == all ? 2U : 0U);
        }
#endif
        std::uint32_t hit_bits = 0;
        std::uint32_t sure_bits = 0;
        for (int k = 0; k < Dim; ++k) {
            const bool hit = a->min[k] <= b->max[k] && b->min[k] <= a->max[k];
            const bool sure = b->max[k] - a->min[k] >= sure_margin_ && a->max[k] - b->min[k] >= sure_margin_;
            hit_bits |= static_cast<std::uint32_t>(hit) << k;
            sure_bits |= static_cast<std::uint32_t>(sure) << k;
        }
        return (hit_bits == all ? 1U : 0U) | (sure_bits == all ? 2U : 0U);
    }


    /// The new candidates of fresh box `p`: the boxes that kept their fat box since the rebuild,
    /// through its cells, and the moved ones directly. A pair of two fresh boxes is found by the
    /// one that comes second.
    template <class Report>
    void find_candidates_of(Position p, Report& report) {
        const Held fat = fat_[p];
        auto add = [&](Position q) {
            reserve_with_slack(candidates_, candidates_.size() + 1);  // not doubling the list
            candidates_.push_back(Candidate{p, q});
            test(p, q, report);
        };
        cells_.for_each_held_overlapping(fat, [&](Slot slot) {
            const Position q = position_of_[slot];
            if ((state_[q] & (kMoved | kGone)) == 0) add(q);
        });
        for (const Position q : moved_) {
            const std::uint8_t state = state_[q];
            if (q == p || (state & kGone) != 0 || ((state & kFresh) != 0 && (state & kDone) == 0)) continue;
            if (overlaps(fat, fat_[q])) add(q);
        }
        state_[p] |= kDone;
    }

    std::span<const Box<Input, Dim>> input_;
    std::array<Input, Dim> origin_{};
    double skin_ = 0;
    float sure_margin_ = 0;
    bool built_ = false;
    bool rebuilt_ = false;
    std::size_t rebuilt_boxes_ = 0;
    std::size_t retested_ = 0;
    std::size_t refreshed_ = 0;
    std::size_t tombstones_ = 0;  // candidates dropped in place (a pair of a position with itself)
    std::size_t kept_since_rebuild_ = kShortLife;  // the first build ends no life
    std::size_t short_lives_ = 0;                  // running
    bool exhausted_ = false;                       // step aside at the next detect()

    PersistentCutPipeline<float, Dim, float> cells_;  // over the fat boxes of the last rebuild
    std::vector<Held> fat_;              // per position
    std::vector<Held> held_;             // per position: this detection's boxes, held as floats; one more of padding
    std::vector<Slot> slot_of_;          // per position: the caller's index
    std::vector<Position> position_of_;  // per slot ever seen since the rebuild
    std::vector<std::uint8_t> state_;    // per position: kMoved, kFresh, kGone, kDone
    std::vector<Position> moved_;        // positions with kMoved, each once
    std::vector<Position> fresh_;        // positions with kFresh, in order
    std::vector<Candidate> candidates_;  // pairs of positions whose fat boxes overlap, each once; and tombstones
    std::vector<Position> gone_;         // positions whose slot left the array in this detection
    std::vector<std::uint64_t> dirty_;   // per position, a bit: fresh or gone in this detection
    int threads_ = 1;
    std::vector<Scan> scans_;            // per thread
    std::vector<Worker> workers_;        // per thread
    std::vector<Block> blocks_;          // two rounds of blocks of candidates (several threads)
    Block serial_;                       // the pass on one thread
};

}  // namespace smb::detail
