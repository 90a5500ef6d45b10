// SPDX-License-Identifier: MIT
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
// candidate's two boxes lie close together in held_ and the pass over the candidates
// (candidate_list.hpp) reads memory almost in order. The caller's array is read once per
// detection, in that order.

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/bulk_vector.hpp"
#include "core/growth.hpp"
#include "core/held_box.hpp"
#include "core/id_index.hpp"
#include "core/input_retest.hpp"
#include "core/prefetch.hpp"
#include "core/stopwatch.hpp"
#include "core/thread_team.hpp"
#include "cuts/persistent_cut_pipeline.hpp"
#include "skin/candidate_list.hpp"
#include "skin/fat_boxes.hpp"
#include "skin/position_names.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"
#include "smb/profile.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

template <std::floating_point Input, int Dim>
class SkinList {
public:
    using Held = Box<float, Dim>;

    /// Reports every overlapping pair of `input` (box i under keys[i], or under i where `keys` is
    /// empty) to report(key_i, key_j), or in runs to report.append(). `keys_kept`: keys[i] names
    /// the box the last detection saw at i but where fold_removals() said (position_names.hpp).
    /// `origin`: where held coordinates start (held_box.hpp; zero for float input). Returns
    /// false, having reported nothing and released its memory, when the fat boxes make more
    /// candidates than it will hold (about 32 per box), when a quarter of the boxes left their fat
    /// boxes since the last detection (a skin far too thin for the motion), or after two short
    /// lives of the candidates running (fat_boxes.hpp): the caller then detects without a
    /// skin.
    template <class Report>
    bool detect(std::span<const Box<Input, Dim>> input, std::span<const BoxId> keys, bool keys_kept,
                const std::array<Input, Dim>& origin, const std::array<Input, Dim>& scene_lo,
                const std::array<Input, Dim>& scene_hi, double skin, const DetectionSettings& settings, Report& report,
                DetectStats& stats, DetectProfile& profile) {
        input_ = input;
        names_.follow(keys, keys_kept);
        threads_ = thread_count(settings);
        sure_margin_ = kExact ? 0.0F : held_sure_margin<Input, Dim>(origin, scene_lo, scene_hi);
        retested_ = 0;
        refreshed_ = 0;
        rebuilt_ = false;
        const std::size_t n = input.size();
        if (exhausted_) {
            clear();
            return false;
        }
        const bool stale =
            !built_ || origin != origin_ || skin != skin_ || 4 * n > 5 * rebuilt_boxes_ || 5 * n < 4 * rebuilt_boxes_;
        try {
            const Outcome outcome = stale ? Outcome::rebuild : step(report, settings.profile, profile);
            if (outcome == Outcome::hopeless) {
                clear();
                return false;
            }
            if (outcome == Outcome::rebuild) {
                origin_ = origin;
                skin_ = skin;
                if (!rebuild(settings, profile)) return false;
                test_candidates(report, false);
            }
        } catch (...) {
            // A sink that threw (or a pair limit) may have left the candidates half compacted:
            // the next detection starts from a rebuild.
            built_ = false;
            throw;
        }
        if (candidates_.size() > candidate_cap(n)) built_ = false;  // let the next rebuild judge
        stats.skin_candidates += candidates_.live();
        stats.skin_refreshed += refreshed_;
        stats.skin_rebuilt = stats.skin_rebuilt || rebuilt_;
        if (lives_.short_again(rebuilt_)) {
            clear();
            exhausted_ = true;
        }
        return true;
    }

    /// Pairs the held floats could not settle, tested again on the input, in the last detection.
    [[nodiscard]] std::size_t retested() const noexcept { return retested_; }
    [[nodiscard]] bool rebuilt() const noexcept { return rebuilt_; }  // the last detection rebuilt

    /// The live candidates of the last detection as pairs of the caller's indices, a < b, in
    /// the order of the list (smb/candidate_pairs.hpp).
    void candidate_pairs(std::vector<Pair>& out) const { candidates_.pairs_named(slot_of_, out); }

    /// The least distance from a box of the last detection to a face of its fat box, on the
    /// caller's coordinates (fat_boxes.hpp).
    [[nodiscard]] double candidate_margin() const noexcept {
        return least_skin_left<kExact, Dim>(held_, fat_, slot_of_, input_.size(), skin_);
    }

    void clear() { *this = SkinList(); }

    /// A World's store moved boxes into the slots of removed ones (position_names.hpp).
    void fold_removals(const SlotRenumbering& renumbering) {
        if (built_) names_.fold_removals(renumbering);
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        std::size_t bytes = cells_.bytes_held() + (fat_.capacity() + held_.capacity()) * sizeof(Held) +
                            (slot_of_.capacity() + position_of_.capacity() + moved_.capacity() + fresh_.capacity()) *
                                sizeof(std::uint32_t) +
                            state_.capacity() + gone_.capacity() * sizeof(Position) + names_.bytes_held() +
                            candidates_.bytes_held();
        return bytes + scans_.bytes_held([](const Scan& scan) {
            return (scan.fresh.capacity() + scan.gone.capacity()) * sizeof(Position);
        });
    }

private:
    using Position = std::uint32_t;
    using Candidates = CandidateList<Dim>;
    /// Below this many positions one thread does the scan alone.
    static constexpr std::size_t kParallelFrom = std::size_t{1} << 15;

    static constexpr bool kExact = std::same_as<Input, float>;  // held boxes are the input's own

    /// The pipeline's pairs of fat boxes become the candidates; positions follow its new order.
    bool rebuild(const DetectionSettings& settings, DetectProfile& profile) {
        rebuilt_ = true;
        const std::size_t n = input_.size();
        // held_ serves as the fat boxes by slot until the positions are known.
        resize_for_overwrite(held_, n + 1);  // and one box of padding for candidate_bits()
        for (std::size_t slot = 0; slot < n; ++slot) held_[slot] = fattened(held_of(input_[slot]), skin_);
        cells_.forget_slots_from(n);
        typename Candidates::Collector collect = candidates_.rebuild(candidate_cap(n));
        try {
            cells_.detect(std::span<const Held>(held_.data(), n), {}, settings, collect, profile);
        } catch (const typename Candidates::TooManyCandidates&) {
            clear();
            return false;
        }
        const std::span<const Slot> order = cells_.order();
        slot_of_.assign(order.begin(), order.end());
        resize_for_overwrite(position_of_, n);
        resize_for_overwrite(fat_, n);
        for (std::size_t p = 0; p < n; ++p) {
            position_of_[slot_of_[p]] = static_cast<Position>(p);
            fat_[p] = held_[slot_of_[p]];
        }
        candidates_.renumber(position_of_);
        gather_held();
        state_.assign(n, 0);
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
            held_[p] = held_of(input_[slot_of_[p]]);
        }
        names_.gather(slot_of_);
    }

    enum class Outcome { kept, rebuild, hopeless };

    /// One detection on the kept candidates; before reporting anything, rebuild when the moved
    /// list would outgrow its limit, hopeless when a quarter of the boxes left their fat boxes
    /// (the skin is far too thin for the motion: a rebuild costs more than no skin).
    template <class Report>
    Outcome step(Report& report, bool timed, DetectProfile& profile) {
        Stopwatch phase{timed};
        const std::size_t n = input_.size();
        const std::size_t known = position_of_.size();
        // Each thread scans a contiguous share of the positions; their lists, joined in thread
        // order, are the lists of one scan.
        scans_.resize(threads_);
        const std::size_t count = slot_of_.size();
        names_.read_moved(position_of_, n);
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
            names_.append(static_cast<Slot>(slot));
            position_of_.push_back(p);
            held_.back() = held_of(input_[slot]);
            held_.push_back(Held{});  // the padding
            fat_.push_back(Held{});
            state_.push_back(0);
            fresh_.push_back(p);
        }
        for (const Position p : fresh_) {
            fat_[p] = fattened(held_[p], skin_);
            std::uint8_t& state = state_[p];
            state &= static_cast<std::uint8_t>(~kGone);
            if ((state & kMoved) == 0) moved_.push_back(p);
            state |= kMoved | kFresh;
        }
        refreshed_ = fresh_.size();
        // The candidates of fresh and gone boxes are dropped: their held boxes vacant (empty)
        // while the candidates are tested, the fresh ones' read again after.
        const bool dropping = !fresh_.empty() || !gone_.empty();
        for (const Position p : fresh_) held_[p] = empty_float_box<Dim>();
        for (const Position p : gone_) held_[p] = empty_float_box<Dim>();
        profile.containment_seconds += phase.lap();

        test_candidates(report, dropping);
        for (const Position p : fresh_) held_[p] = held_of(input_[slot_of_[p]]);
        for (const Position p : fresh_) find_candidates_of(p, report);
        for (const Position p : fresh_) state_[p] &= static_cast<std::uint8_t>(~(kFresh | kDone));
        profile.check_seconds += phase.seconds();
        return Outcome::kept;
    }

    /// What one thread's share of the containment check found.
    struct Scan {
        std::vector<Position> fresh;  // boxes out of their fat box, or back in the array
        std::vector<Position> gone;   // positions whose slot just left the array
        std::size_t newly_moved = 0;  // of the fresh ones, those not moved since the rebuild
    };

    /// Positions [first, last): the caller's boxes as held floats into held_, and each checked
    /// against its fat box. A pass for each way of naming, so that the loop holds no test of it.
    void scan(std::size_t first, std::size_t last, Scan& found) {
        if (names_.reread())
            scan_as<true>(first, last, found);
        else
            scan_as<false>(first, last, found);
    }

    template <bool reread>
    void scan_as(std::size_t first, std::size_t last, Scan& found) {
        const std::size_t n = input_.size();
        constexpr std::size_t ahead = 32;
        const Slot* slot_of = slot_of_.data();
        const Box<Input, Dim>* input = input_.data();
        std::uint8_t* states = state_.data();
        const Held* fat_of = fat_.data();
        Held* held_of_position = held_.data();
        for (std::size_t p = first; p < last; ++p) {
            const Slot slot = slot_of[p];
            if (slot >= n) [[unlikely]] {
                if ((states[p] & kGone) == 0) {
                    states[p] |= kGone;
                    found.gone.push_back(static_cast<Position>(p));
                }
                continue;
            }
            if (p + ahead < last) {
                const Slot next = slot_of[p + ahead];
                if (next < n) {
                    prefetch_whole(&input[next]);
                    if constexpr (reread) names_.prefetch(next);
                }
            }
            const Held held = held_of(input[slot]);
            if constexpr (reread) names_.read(static_cast<Position>(p), slot);
            // Read before held_[p] is written: the two arrays start alike modulo 4 KiB (each its
            // own mapping), so the load after the store would wait on it (4K aliasing).
            const Held fat = fat_of[p];
            held_of_position[p] = held;
            const std::uint8_t state = states[p];
            if (((state & kGone) != 0) | !inside(held, fat)) [[unlikely]] {
                names_.read(static_cast<Position>(p), slot);  // a slot back in the array has a new name
                found.fresh.push_back(static_cast<Position>(p));
                found.newly_moved += (state & kMoved) == 0 ? 1U : 0U;
            }
        }
    }

    /// The caller's box as the list holds it: itself where it is of floats (the origin is then
    /// zero and every coordinate finite), else shifted and rounded (held_box.hpp).
    [[nodiscard]] Held held_of(const Box<Input, Dim>& box) const noexcept {
        return held_as<float, Input, Dim>(box, origin_);
    }

    /// Held boxes at a and b overlap: true when their input boxes do too. `sure`: the floats
    /// proved it (overlap_bits()); otherwise the input is asked, and `retested` counts it.
    [[nodiscard]] bool confirmed(Position a, Position b, bool sure, std::size_t& retested) const {
        return confirmed_on_input<float>(input_, std::span<const Slot>(slot_of_), a, b, sure,
                                         [&retested] { ++retested; });
    }

    template <class Report>
    void test(Position a, Position b, Report& report) {
        const std::uint32_t bits = overlap_bits<Dim>(&held_[a], &held_[b], sure_margin_);
        if ((bits & 1U) != 0 && confirmed(a, b, (bits & 2U) != 0, retested_))
            report(names_(a, slot_of_), names_(b, slot_of_));
    }

    /// Tests every candidate (candidate_list.hpp), after dropping those of vacant held boxes
    /// when `dropping`, and reports the pairs in the order of the list.
    template <class Report>
    void test_candidates(Report& report, bool dropping) {
        auto confirm = [this](Position a, Position b, bool sure, std::size_t& retested) {
            return confirmed(a, b, sure, retested);
        };
        auto test_named = [&]<class Name>(std::span<const Name> names) {
            const typename Candidates::template Pass<decltype(confirm), Name> pass{held_.data(), sure_margin_, names,
                                                                                   confirm, kExact};
            retested_ += candidates_.test(pass, dropping, threads_, report);
        };
        if (names_.named())
            test_named(names_.keys_of_positions());
        else
            test_named(std::span<const Slot>(slot_of_));
    }

    /// The new candidates of fresh box `p`: the boxes that kept their fat box since the rebuild,
    /// through its cells, and the moved ones directly. A pair of two fresh boxes is found by the
    /// one that comes second.
    template <class Report>
    void find_candidates_of(Position p, Report& report) {
        const Held fat = fat_[p];
        auto add = [&](Position q) {
            candidates_.add(p, q);
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
    CandidateLives lives_;
    bool exhausted_ = false;  // step aside at the next detect()

    // The last rebuild's fat boxes in small cells, where a box that left its skin finds its neighbours.
    PersistentCutPipeline<float, Dim, float> cells_{CellShape::cut_on_every_axis};
    BulkVector<Held> fat_;              // per position
    BulkVector<Held> held_;             // per position: this detection's boxes, held as floats; one more of padding
    BulkVector<Slot> slot_of_;          // per position: the caller's index
    PositionNames names_;               // what each position is reported under
    BulkVector<Position> position_of_;  // per slot ever seen since the rebuild
    BulkVector<std::uint8_t> state_;    // per position: kMoved, kFresh, kGone, kDone
    std::vector<Position> moved_;       // positions with kMoved, each once
    std::vector<Position> fresh_;       // positions with kFresh, in order
    Candidates candidates_;             // pairs of positions whose fat boxes overlap
    std::vector<Position> gone_;        // positions whose slot left the array in this detection
    int threads_ = 1;
    PerThread<Scan> scans_;
};

}  // namespace smb::detail
