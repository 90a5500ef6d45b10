// SPDX-License-Identifier: MIT
#include "smb/mpi/distributed_detector.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>
#include <string>

#include "axial_regions.hpp"
#include "collective_checks.hpp"
#include "exchange.hpp"
#include "smb/detector.hpp"

namespace smb::mpi {

namespace detail {

/// A box on its way to a region, under its global id.
template <std::floating_point Real, int Dim>
struct BoxRecord {
    BoxId id;
    Box<Real, Dim> box;
};

template <std::floating_point Real, int Dim>
class DistributedState {
public:
    using box_type = Box<Real, Dim>;

    DistributedState(MPI_Comm comm, const DistributedSettings& settings) : settings_(settings) {
        if (!(settings.rebalance_threshold >= 1)) {
            throw ArgumentError("DistributedSettings::rebalance_threshold must be at least 1, not " +
                                std::to_string(settings.rebalance_threshold));
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
    /// Sends every box to each region it meets; fills region_ids_, region_boxes_, holders_.
    void send_boxes_to_regions(std::span<const BoxId> ids, std::span<const box_type> boxes);
    /// Runs the Detector over the region and sends each pair kept here to its holder(s).
    std::vector<Pair> detect_in_region_and_hand_off();

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
    std::vector<BoxId> checked_ids_;  // the ids of the last step that passed the checks
    bool has_checked_ids_ = false;
    std::vector<BoxId> region_ids_;
    std::vector<box_type> region_boxes_;
    std::vector<int> holders_;  // the rank that passed in each of the region's boxes
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
    // An id set that is the same, in the same order, as the last step's cannot hold a new
    // repeat; anything else (an insertion, a removal, a box moved between ranks) is checked.
    local.ids_changed =
        !has_checked_ids_ || !std::equal(ids.begin(), ids.end(), checked_ids_.begin(), checked_ids_.end());
    const GlobalInputFindings global = agree_on_input(comm_, local, n, region_counts);
    stats_.id_bytes_sent = 0;
    if (global.ids_changed_anywhere) stats_.id_bytes_sent = check_ids_unique(comm_, ids);
    if (local.ids_changed) checked_ids_.assign(ids.begin(), ids.end());
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
void DistributedState<Real, Dim>::send_boxes_to_regions(std::span<const BoxId> ids, std::span<const box_type> boxes) {
    using Record = BoxRecord<Real, Dim>;
    std::vector<int> destinations;  // the regions of each box, box after box
    std::vector<std::size_t> first(boxes.size() + 1, 0);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        regions_.regions_of(boxes[i], destinations);
        first[i + 1] = destinations.size();
    }
    std::vector<int> counts(static_cast<std::size_t>(ranks_), 0);
    for (int region : destinations) ++counts[static_cast<std::size_t>(region)];
    std::vector<int> fill(counts.size(), 0);
    std::exclusive_scan(counts.begin(), counts.end(), fill.begin(), 0);
    std::vector<Record> send(destinations.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        for (std::size_t d = first[i]; d < first[i + 1]; ++d) {
            send[static_cast<std::size_t>(fill[static_cast<std::size_t>(destinations[d])]++)] =
                Record{ids[i], boxes[i]};
        }
    }
    std::vector<int> receive_counts;
    const std::vector<Record> received = all_to_all(comm_, send, counts, receive_counts);
    stats_.box_bytes_sent = bytes_to_others<Record>(counts, rank_);

    region_ids_.resize(received.size());
    region_boxes_.resize(received.size());
    holders_.resize(received.size());
    std::size_t at = 0;
    stats_.boxes_owned = 0;
    for (int source = 0; source < ranks_; ++source) {
        for (int r = 0; r < receive_counts[static_cast<std::size_t>(source)]; ++r, ++at) {
            region_ids_[at] = received[at].id;
            region_boxes_[at] = received[at].box;
            holders_[at] = source;
            if (regions_.region_of(centre_of(received[at].box)) == rank_) ++stats_.boxes_owned;
        }
    }
    stats_.boxes_in_region = received.size();
}

template <std::floating_point Real, int Dim>
std::vector<Pair> DistributedState<Real, Dim>::detect_in_region_and_hand_off() {
    struct Addressed {
        int destination;
        Pair pair;
    };
    std::vector<Addressed> kept;
    const bool both = settings_.hand_off == PairHandOff::both_holders;
    const auto start = std::chrono::steady_clock::now();
    // The sink streams the pairs, so no pair limit applies here: a limit reached on one rank
    // alone would leave the others waiting in the exchange.
    detector_.detect(std::span<const box_type>(region_boxes_), [&](std::span<const Pair> chunk) {
        for (const Pair& local : chunk) {
            if (!lower_corner_is_here(region_boxes_[local.a], region_boxes_[local.b])) continue;
            std::size_t first = local.a, second = local.b;
            if (region_ids_[second] < region_ids_[first]) std::swap(first, second);
            const Pair pair{region_ids_[first], region_ids_[second]};
            kept.push_back({holders_[first], pair});
            if (both && holders_[second] != holders_[first]) kept.push_back({holders_[second], pair});
        }
    });
    stats_.local_detect_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats_.pairs_found = 0;
    std::vector<int> counts(static_cast<std::size_t>(ranks_), 0);
    for (const Addressed& item : kept) ++counts[static_cast<std::size_t>(item.destination)];
    std::vector<int> fill(counts.size(), 0);
    std::exclusive_scan(counts.begin(), counts.end(), fill.begin(), 0);
    std::vector<Pair> send(kept.size());
    for (const Addressed& item : kept)
        send[static_cast<std::size_t>(fill[static_cast<std::size_t>(item.destination)]++)] = item.pair;
    stats_.pairs_found = both ? 0 : kept.size();
    if (both) {
        for (std::size_t i = 0; i < kept.size(); ++i) {
            // The second copy of a pair follows its first, addressed to the other holder.
            if (i + 1 < kept.size() && kept[i + 1].pair == kept[i].pair) ++i;
            ++stats_.pairs_found;
        }
    }
    std::vector<int> receive_counts;
    std::vector<Pair> received = all_to_all(comm_, send, counts, receive_counts);
    stats_.pair_bytes_sent = bytes_to_others<Pair>(counts, rank_);
    return received;
}

template <std::floating_point Real, int Dim>
void DistributedState<Real, Dim>::detect(std::span<const BoxId> ids, std::span<const box_type> boxes,
                                         std::vector<Pair>& pairs) {
    const auto start = std::chrono::steady_clock::now();
    stats_ = DistributedStats{};
    agree_and_balance(ids, boxes);
    stats_.boxes_passed = boxes.size();
    send_boxes_to_regions(ids, boxes);
    std::vector<Pair> received = detect_in_region_and_hand_off();
    stats_.pairs_received = received.size();
    pairs.swap(received);
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
