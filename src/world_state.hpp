#pragma once
// TEMPORARY: brute-force detection while the SMB pipeline is written.

#include <chrono>
#include <vector>

#include "box_store.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"
#include "smb/world.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class WorldState {
public:
    explicit WorldState(const WorldSettings& settings) : settings_(settings) {}

    BoxStore<Real, Dim>& store() noexcept { return store_; }
    const BoxStore<Real, Dim>& store() const noexcept { return store_; }
    const WorldSettings& settings() const noexcept { return settings_; }
    const DetectStats& last_stats() const noexcept { return stats_; }
    std::size_t bytes_held() const noexcept { return store_.bytes_held(); }
    void clear() { store_.clear(); }

    DetectStats detect(const PairSink& sink) {
        if (store_.has_removals()) store_.compact();
        std::vector<Pair> out;
        const auto n = static_cast<Slot>(store_.slot_count());
        for (Slot i = 0; i < n; ++i)
            for (Slot j = i + 1; j < n; ++j)
                if (overlaps(store_.box_at(i), store_.box_at(j))) {
                    BoxId a = store_.id_at(i), b = store_.id_at(j);
                    if (a > b) std::swap(a, b);
                    out.push_back({a, b});
                }
        if (!out.empty()) sink(out);
        stats_ = {};
        stats_.boxes = n;
        stats_.pairs = out.size();
        stats_.bytes_held = bytes_held();
        return stats_;
    }

private:
    WorldSettings settings_;
    BoxStore<Real, Dim> store_;
    DetectStats stats_;
};

}  // namespace smb::detail
