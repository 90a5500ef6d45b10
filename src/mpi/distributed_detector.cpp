// SPDX-License-Identifier: MIT
#include "smb/mpi/distributed_detector.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <numeric>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "axial_regions.hpp"
#include "core/shortest_number.hpp"
#include "distributed_id_set.hpp"
#include "exchange.hpp"
#include "region_store.hpp"
#include "smb/detector.hpp"
#include "smb/errors.hpp"

namespace smb::mpi {

namespace detail {

/// A box on its way to a region, under its global id.
template <std::floating_point Real, int Dim>
struct BoxRecord {
    BoxId id;
    Box<Real, Dim> box;
};

/// What a rank sent to the regions at its last step: each of its boxes, in id order, and the
/// regions it went to. Against it, a step sends only what changed (docs/distributed.md).
template <class Box>
struct SentBoxes {
    std::vector<BoxId> ids;  ///< increasing
    std::vector<Box> boxes;
    std::vector<std::size_t> first{0};  ///< box i went to regions[first[i] .. first[i + 1])
    std::vector<int> regions;

    [[nodiscard]] std::size_t size() const noexcept { return ids.size(); }
    [[nodiscard]] std::span<const int> regions_of(std::size_t i) const noexcept {
        return std::span<const int>(regions).subspan(first[i], first[i + 1] - first[i]);
    }
    void clear() {
        ids.clear();
        boxes.clear();
        first.assign(1, 0);
        regions.clear();
    }
    void add(BoxId id, const Box& box, std::span<const int> to) {
        ids.push_back(id);
        boxes.push_back(box);
        regions.insert(regions.end(), to.begin(), to.end());
        first.push_back(regions.size());
    }
};

/// What each rank found in its own input, to be summed over the ranks.
struct LocalInputFindings {
    bool lengths_differ = false;    ///< ids and boxes of different lengths
    bool has_invalid_box = false;   ///< a box with NaN, infinity or min > max
    BoxId smallest_invalid_id = 0;  ///< the smallest id of such a box
    bool ids_changed = false;       ///< the ids differ from the last step's
};

/// What the ranks found together.
struct GlobalInputFindings {
    bool ids_changed_anywhere = false;
    unsigned long long total_boxes = 0;
};

/// Sums the findings (and `region_counts`, in place, in the same reduction) over the ranks, and
/// throws on every rank, with the same message, ArgumentError or InvalidBoxError when any
/// rank's input was bad: all ranks agree on it before any exchange, so that bad input anywhere
/// makes every rank throw instead of leaving some in a collective. Collective.
GlobalInputFindings agree_on_input(MPI_Comm comm, const LocalInputFindings& local, std::size_t local_boxes,
                                   std::span<unsigned long long> region_counts) {
    enum : std::size_t { lengths_differ, invalid_box, ids_changed, total_boxes, header };
    std::vector<unsigned long long> sums(header + region_counts.size(), 0);
    sums[lengths_differ] = local.lengths_differ ? 1 : 0;
    sums[invalid_box] = local.has_invalid_box ? 1 : 0;
    sums[ids_changed] = local.ids_changed ? 1 : 0;
    sums[total_boxes] = local_boxes;
    std::copy(region_counts.begin(), region_counts.end(), sums.begin() + header);
    MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(sums.size()), MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
    if (sums[lengths_differ] != 0) {
        throw ArgumentError("DistributedDetector::detect: ids and boxes differ in length on " +
                            std::to_string(sums[lengths_differ]) + " rank(s)");
    }
    if (sums[invalid_box] != 0) {
        // The smallest of the ids that the ranks name (each rank names its own, or none).
        unsigned long long id =
            local.has_invalid_box ? local.smallest_invalid_id : std::numeric_limits<unsigned long long>::max();
        MPI_Allreduce(MPI_IN_PLACE, &id, 1, MPI_UNSIGNED_LONG_LONG, MPI_MIN, comm);
        throw InvalidBoxError("DistributedDetector::detect: box " + std::to_string(id) +
                              " is invalid (a NaN or infinite coordinate, or min > max); " +
                              std::to_string(sums[invalid_box]) + " rank(s) hold invalid boxes");
    }
    std::copy(sums.begin() + header, sums.end(), region_counts.begin());
    return {sums[ids_changed] != 0, sums[total_boxes]};
}

template <std::floating_point Real, int Dim>
class DistributedState {
public:
    using box_type = Box<Real, Dim>;

    DistributedState(MPI_Comm comm, const DistributedSettings& settings) : settings_(settings) {
        if (!(settings.rebalance_threshold >= 1)) {
            throw ArgumentError("DistributedSettings::rebalance_threshold must be at least 1, not " +
                                smb::detail::shortest_number(settings.rebalance_threshold));
        }
        MPI_Comm_dup(comm, &comm_);
        MPI_Comm_rank(comm_, &rank_);
        MPI_Comm_size(comm_, &ranks_);
        regions_ = AxialRegions<Real, Dim>(ranks_);
        region_ = regions_.bounds(rank_);
        detector_ = Detector<Real, Dim>(settings.detector);
    }

    ~DistributedState() {
        int finalized = 0;
        MPI_Finalized(&finalized);
        if (!finalized) MPI_Comm_free(&comm_);
    }
    DistributedState(const DistributedState&) = delete;
    DistributedState& operator=(const DistributedState&) = delete;

    void detect(std::span<const BoxId> ids, std::span<const box_type> boxes, std::vector<Pair>& pairs);

    DistributedSettings settings_;
    DistributedStats stats_;
    AxialRegions<Real, Dim> regions_;
    Box<double, Dim> region_{};

private:
    /// Checks this rank's input, then agrees with the others (throws on every rank alike) and
    /// recuts when the population is out of balance. Collective.
    void agree_and_balance(std::span<const BoxId> ids, std::span<const box_type> boxes);
    /// Sends to each region the boxes that changed for it since the last step (all of them
    /// after a recut) and updates store_ with what the others sent here.
    void send_box_changes(std::span<const box_type> boxes);
    /// Applies what arrived: the removals first, so that a box moving between ranks (removed by
    /// one, inserted by another) ends held by the second.
    void receive_box_changes(const std::vector<BoxId>& removals, const std::vector<BoxRecord<Real, Dim>>& upserts,
                             const std::vector<int>& upsert_counts);
    /// Runs the Detector over the region and sends each pair kept here to its holder(s); what
    /// arrives here goes to pairs_received_.
    void detect_in_region_and_hand_off();

    [[nodiscard]] bool lower_corner_is_here(const box_type& a, const box_type& b) const noexcept {
        for (int k = 0; k < Dim; ++k) {
            const double corner = static_cast<double>(std::max(a.min[k], b.min[k]));
            if (!(region_.min[k] <= corner && corner < region_.max[k])) return false;
        }
        return true;
    }

    MPI_Comm comm_ = MPI_COMM_NULL;
    int rank_ = 0;
    int ranks_ = 1;
    Detector<Real, Dim> detector_;
    DistributedIdSet id_set_;
    bool has_checked_ids_ = false;
    std::vector<std::size_t> order_;  // this step's boxes in id order
    std::vector<BoxId> sorted_ids_;
    SentBoxes<box_type> sent_;
    SentBoxes<box_type> next_sent_;                            // this step's, swapped into sent_
    std::vector<std::pair<int, std::size_t>> upsert_targets_;  // (region, box in id order)
    std::vector<std::pair<int, BoxId>> removal_targets_;       // (region, id)
    std::vector<BoxRecord<Real, Dim>> upsert_send_;
    std::vector<BoxId> removal_send_;
    std::vector<int> here_;
    std::vector<BoxId> removals_received_;
    std::vector<BoxRecord<Real, Dim>> upserts_received_;
    std::vector<std::pair<int, Pair>> kept_pairs_;  // (holder, pair): kept here, on its way
    std::vector<Pair> pair_send_;
    std::vector<Pair> pairs_received_;  // swapped with the caller's vector
    RegionStore<box_type> store_;       // the region's boxes, with the rank that passed in each
};

template <std::floating_point Real, int Dim>
void DistributedState<Real, Dim>::agree_and_balance(std::span<const BoxId> ids, std::span<const box_type> boxes) {
    LocalInputFindings local;
    local.lengths_differ = ids.size() != boxes.size();
    const std::size_t n = std::min(ids.size(), boxes.size());
    std::vector<unsigned long long> region_counts(regions_.has_cuts() ? static_cast<std::size_t>(ranks_) : 0, 0);
    for (std::size_t i = 0; i < n; ++i) {
        if (!is_valid(boxes[i])) {
            local.smallest_invalid_id = local.has_invalid_box ? std::min(local.smallest_invalid_id, ids[i]) : ids[i];
            local.has_invalid_box = true;
        } else if (!region_counts.empty()) {
            ++region_counts[static_cast<std::size_t>(regions_.region_of(centre_of(boxes[i])))];
        }
    }
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), std::size_t{0});
    const auto by_id = [&ids](std::size_t x, std::size_t y) { return ids[x] < ids[y]; };
    if (!std::is_sorted(order_.begin(), order_.end(), by_id)) std::stable_sort(order_.begin(), order_.end(), by_id);
    sorted_ids_.resize(n);
    for (std::size_t k = 0; k < n; ++k) sorted_ids_[k] = ids[order_[k]];
    // An id set that is the same as the last step's cannot hold a new repeat; anything else (an
    // insertion, a removal, a box moved between ranks) is checked.
    const auto last_ids = id_set_.last_ids();
    local.ids_changed =
        !has_checked_ids_ || !std::equal(sorted_ids_.begin(), sorted_ids_.end(), last_ids.begin(), last_ids.end());
    const GlobalInputFindings global = agree_on_input(comm_, local, n, region_counts);
    stats_.id_bytes_sent = 0;
    if (global.ids_changed_anywhere) stats_.id_bytes_sent = id_set_.check_and_record(comm_, sorted_ids_);
    has_checked_ids_ = true;

    const double mean = static_cast<double>(global.total_boxes) / static_cast<double>(ranks_);
    const unsigned long long most =
        region_counts.empty() ? 0 : *std::max_element(region_counts.begin(), region_counts.end());
    stats_.imbalance = mean > 0 ? static_cast<double>(most) / mean : 0;
    stats_.recut = !regions_.has_cuts() || stats_.imbalance > settings_.rebalance_threshold;
    if (stats_.recut) {
        regions_.recut(comm_, boxes);
        region_ = regions_.bounds(rank_);
    }
}

template <std::floating_point Real, int Dim>
void DistributedState<Real, Dim>::send_box_changes(std::span<const box_type> boxes) {
    using Record = BoxRecord<Real, Dim>;
    if (stats_.recut) {
        // Other regions: every box goes anew to the regions it meets.
        sent_.clear();
        store_.clear();
    }
    const auto contains = [](std::span<const int> list, int region) {
        return std::find(list.begin(), list.end(), region) != list.end();
    };
    // First the destinations (region, box), then a counting sort into the send buffers; the
    // buffers are members, so that a step reuses the last one's memory.
    upsert_targets_.clear();
    removal_targets_.clear();
    const auto remove_everywhere = [&](std::size_t last) {
        for (int region : sent_.regions_of(last)) removal_targets_.push_back({region, sent_.ids[last]});
    };
    next_sent_.clear();
    std::size_t last = 0;  // both in id order: a merge
    for (std::size_t k = 0; k < order_.size(); ++k) {
        const BoxId id = sorted_ids_[k];
        const box_type& box = boxes[order_[k]];
        here_.clear();
        regions_.regions_of(box, here_);
        while (last < sent_.size() && sent_.ids[last] < id) remove_everywhere(last++);
        const bool known = last < sent_.size() && sent_.ids[last] == id;
        const std::span<const int> before = known ? sent_.regions_of(last) : std::span<const int>();
        const bool moved = !known || !(sent_.boxes[last] == box);
        for (int region : here_) {
            if (moved || !contains(before, region)) upsert_targets_.push_back({region, k});
        }
        for (int region : before) {
            if (!contains(here_, region)) removal_targets_.push_back({region, id});
        }
        if (known) ++last;
        next_sent_.add(id, box, here_);
    }
    while (last < sent_.size()) remove_everywhere(last++);
    std::swap(sent_, next_sent_);

    std::vector<int> removal_counts, upsert_counts, removals_received, upserts_received;
    sort_by_rank(removal_targets_, ranks_, removal_send_, removal_counts, [](BoxId id) { return id; });
    sort_by_rank(upsert_targets_, ranks_, upsert_send_, upsert_counts, [&](std::size_t k) {
        return Record{sorted_ids_[k], boxes[order_[k]]};
    });
    stats_.box_bytes_sent = all_to_all(comm_, removal_send_, removal_counts, removals_received, removals_received_);
    stats_.box_bytes_sent += all_to_all(comm_, upsert_send_, upsert_counts, upserts_received, upserts_received_);
    receive_box_changes(removals_received_, upserts_received_, upserts_received);
}

template <std::floating_point Real, int Dim>
void DistributedState<Real, Dim>::receive_box_changes(const std::vector<BoxId>& removals,
                                                      const std::vector<BoxRecord<Real, Dim>>& upserts,
                                                      const std::vector<int>& upsert_counts) {
    for (BoxId id : removals) store_.remove(id);
    store_.reserve(store_.size() + upserts.size());
    std::size_t at = 0;
    for (int source = 0; source < ranks_; ++source) {
        for (int r = 0; r < upsert_counts[static_cast<std::size_t>(source)]; ++r, ++at) {
            store_.upsert(upserts[at].id, upserts[at].box, source);
        }
    }
    stats_.boxes_owned = 0;
    for (const box_type& box : store_.boxes()) {
        if (regions_.region_of(centre_of(box)) == rank_) ++stats_.boxes_owned;
    }
    stats_.boxes_in_region = store_.size();
}

template <std::floating_point Real, int Dim>
void DistributedState<Real, Dim>::detect_in_region_and_hand_off() {
    std::vector<std::pair<int, Pair>>& kept = kept_pairs_;
    kept.clear();
    const bool both = settings_.hand_off == PairHandOff::both_holders;
    std::size_t found = 0;
    const auto start = std::chrono::steady_clock::now();
    // The sink streams the pairs, so no pair limit applies here: a limit reached on one rank
    // alone would leave the others waiting in the exchange.
    const auto& region_ids = store_.ids();
    const auto& region_boxes = store_.boxes();
    const auto& holders = store_.holders();
    detector_.detect(std::span<const box_type>(region_boxes), [&](std::span<const Pair> chunk) {
        for (const Pair& local : chunk) {
            if (!lower_corner_is_here(region_boxes[local.a], region_boxes[local.b])) continue;
            std::size_t first = local.a, second = local.b;
            if (region_ids[second] < region_ids[first]) std::swap(first, second);
            const Pair pair{region_ids[first], region_ids[second]};
            kept.push_back({holders[first], pair});
            if (both && holders[second] != holders[first]) kept.push_back({holders[second], pair});
            ++found;
        }
    });
    stats_.local_detect_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats_.pairs_found = found;
    std::vector<int> counts;
    sort_by_rank(kept, ranks_, pair_send_, counts, [](const Pair& pair) { return pair; });
    std::vector<int> receive_counts;
    stats_.pair_bytes_sent = all_to_all(comm_, pair_send_, counts, receive_counts, pairs_received_);
}

template <std::floating_point Real, int Dim>
void DistributedState<Real, Dim>::detect(std::span<const BoxId> ids, std::span<const box_type> boxes,
                                         std::vector<Pair>& pairs) {
    const auto start = std::chrono::steady_clock::now();
    stats_ = DistributedStats{};
    agree_and_balance(ids, boxes);
    stats_.boxes_passed = boxes.size();
    send_box_changes(boxes);
    detect_in_region_and_hand_off();
    stats_.pairs_received = pairs_received_.size();
    // The caller's vector takes the pairs; its memory serves the next step's exchange.
    pairs.swap(pairs_received_);
    stats_.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace detail

template <std::floating_point Real, int Dim>
DistributedDetector<Real, Dim>::DistributedDetector(MPI_Comm comm, const DistributedSettings& settings)
    : state_(std::make_unique<detail::DistributedState<Real, Dim>>(comm, settings)) {}

template <std::floating_point Real, int Dim>
DistributedDetector<Real, Dim>::~DistributedDetector() = default;

template <std::floating_point Real, int Dim>
void DistributedDetector<Real, Dim>::detect(std::span<const BoxId> ids, std::span<const box_type> boxes,
                                            std::vector<Pair>& pairs) {
    state_->detect(ids, boxes, pairs);
}

template <std::floating_point Real, int Dim>
const DistributedSettings& DistributedDetector<Real, Dim>::settings() const noexcept {
    return state_->settings_;
}

template <std::floating_point Real, int Dim>
const DistributedStats& DistributedDetector<Real, Dim>::last_stats() const noexcept {
    return state_->stats_;
}

template <std::floating_point Real, int Dim>
std::vector<int> DistributedDetector<Real, Dim>::regions_per_axis() const {
    const auto& per_axis = state_->regions_.per_axis();
    return {per_axis.begin(), per_axis.end()};
}

template <std::floating_point Real, int Dim>
Box<double, Dim> DistributedDetector<Real, Dim>::region() const {
    return state_->region_;
}

template class DistributedDetector<float, 2>;
template class DistributedDetector<float, 3>;
template class DistributedDetector<double, 2>;
template class DistributedDetector<double, 3>;

}  // namespace smb::mpi
