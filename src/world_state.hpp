#pragma once
// What a World holds: its boxes (box_store.hpp), its settings, and the pipeline that finds the
// overlapping pairs, chosen by WorldSettings::pipeline. The pairs are handed to the caller's
// sink in chunks from here, whichever pipeline found them.

#include <chrono>
#include <algorithm>
#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "box_store.hpp"
#include "paper_pipeline.hpp"
#include "persistent_cut_pipeline.hpp"
#include "smb/errors.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"
#include "smb/world.hpp"

namespace smb::detail {

/// Hands pairs to the caller's sink in chunks of the settings' size: one pair at a time (the
/// paper's pipeline) or a run of pairs already in (a < b) order (the persistent pipeline, whose
/// runs go to the sink without another copy where they fill whole chunks).
class PairOutput {
public:
    PairOutput(std::vector<Pair>& chunk, std::size_t chunk_size, const PairSink& sink, std::size_t& count)
        : chunk_(chunk), chunk_size_(chunk_size), sink_(sink), count_(count) {}

    void operator()(BoxId a, BoxId b) {
        if (b < a) std::swap(a, b);
        chunk_.push_back(Pair{a, b});
        if (chunk_.size() == chunk_size_) send_chunk();
    }

    void append(std::span<const Pair> ordered) {
        while (!ordered.empty()) {
            if (chunk_.empty() && ordered.size() >= chunk_size_) {
                count_ += chunk_size_;
                sink_(ordered.first(chunk_size_));
                ordered = ordered.subspan(chunk_size_);
                continue;
            }
            const std::size_t take = std::min(ordered.size(), chunk_size_ - chunk_.size());
            chunk_.insert(chunk_.end(), ordered.begin(), ordered.begin() + static_cast<std::ptrdiff_t>(take));
            ordered = ordered.subspan(take);
            if (chunk_.size() == chunk_size_) send_chunk();
        }
    }

    void flush() {
        if (!chunk_.empty()) send_chunk();
    }

private:
    void send_chunk() {
        count_ += chunk_.size();
        sink_(chunk_);
        chunk_.clear();
    }

    std::vector<Pair>& chunk_;
    std::size_t chunk_size_;
    const PairSink& sink_;
    std::size_t& count_;
};

template <std::floating_point Real, int Dim>
class WorldState {
public:
    explicit WorldState(const WorldSettings& settings) : settings_(validated(settings)) {}
    WorldState(const WorldState&) = delete;
    WorldState& operator=(const WorldState&) = delete;

    BoxStore<Real, Dim>& store() noexcept { return store_; }
    const BoxStore<Real, Dim>& store() const noexcept { return store_; }
    const WorldSettings& settings() const noexcept { return settings_; }
    const DetectStats& last_stats() const noexcept { return stats_; }

    /// Forgets every box and gives back every array, as a new world would have them.
    void clear() {
        store_ = BoxStore<Real, Dim>();
        persistent_ = PersistentCutPipeline<Real, Dim>();
        paper_ = PaperPipeline<Real, Dim>(&store_, &settings_);
        std::vector<Pair>().swap(chunk_);
        stats_ = {};
    }

    DetectStats detect(const PairSink& sink) {
        using Clock = std::chrono::steady_clock;
        const auto start = Clock::now();
        DetectStats stats;
        if (store_.has_removals()) {
            const std::vector<Slot> new_slot = store_.compact();
            if (settings_.pipeline == Pipeline::paper_lists) paper_.fold_removals(new_slot);
            else persistent_.fold_removals(new_slot);
        }
        stats.boxes = store_.slot_count();
        stats.update_seconds = std::chrono::duration<double>(Clock::now() - start).count();

        chunk_.clear();
        chunk_.reserve(settings_.pair_chunk_size);
        PairOutput output{chunk_, settings_.pair_chunk_size, sink, stats.pairs};
        if (settings_.pipeline == Pipeline::paper_lists) {
            auto report_slots = [&](Slot a, Slot b) { output(store_.id_at(a), store_.id_at(b)); };
            paper_.detect(report_slots, stats);
        } else {
            persistent_.detect(store_, settings_, output, stats);
        }
        output.flush();
        stats.bytes_held = bytes_held();
        stats.total_seconds = std::chrono::duration<double>(Clock::now() - start).count();
        stats_ = stats;
        return stats;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        // World allocates this state itself, so its own size counts too.
        return sizeof(*this) + store_.bytes_held() + persistent_.bytes_held() + paper_.bytes_held() +
               chunk_.capacity() * sizeof(Pair);
    }

private:
    static constexpr std::size_t kMaxThreads = 1024;

    static WorldSettings validated(const WorldSettings& settings) {
        if (settings.target_cell_population == 0)
            throw ArgumentError("WorldSettings::target_cell_population must be at least 1");
        if (settings.pair_chunk_size == 0)
            throw ArgumentError("WorldSettings::pair_chunk_size must be at least 1");
        if (settings.pipeline != Pipeline::persistent_cuts && settings.pipeline != Pipeline::paper_lists)
            throw ArgumentError("WorldSettings::pipeline is not a known Pipeline");
        if (settings.threads > kMaxThreads)
            throw ArgumentError("WorldSettings::threads must be at most " + std::to_string(kMaxThreads) +
                                " (0: as many as OpenMP offers), not " + std::to_string(settings.threads));
        return settings;
    }

    WorldSettings settings_;
    BoxStore<Real, Dim> store_;
    DetectStats stats_;
    PersistentCutPipeline<Real, Dim> persistent_;
    PaperPipeline<Real, Dim> paper_{&store_, &settings_};
    std::vector<Pair> chunk_;
};

}  // namespace smb::detail
