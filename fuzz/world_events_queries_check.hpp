// SPDX-License-Identifier: MIT
#pragma once
// What world_ops_check.hpp also checks after each detection it makes: the pair events
// (smb/pair_events.hpp) against a model of begin and end, and the region queries and ray casts
// (World::query, World::cast_ray) against brute force over the same boxes. They read no bytes
// of the input, so every input means what it meant before.

#include <algorithm>
#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <vector>

#include "operation_input.hpp"
#include "smb/pair_events.hpp"
#include "smb/query.hpp"
#include "smb/world.hpp"

namespace smb::fuzz::world_ops_detail {

/// The events a World's detection owes: the list of the previous detection with events, and
/// what happened to the ids since the last completed detection of any kind (which is all a
/// world remembers of removals: docs/events.md).
class EventsModel {
public:
    void note_removed(BoxId id) { removed_.insert(id); }
    void note_cleared() { cleared_ = true; }
    /// A completed detection without events: the world forgot its removals.
    void forget_removals() {
        removed_.clear();
        cleared_ = false;
    }

    /// After a completed detection with events, `now` being the pairs (sorted) and `present`
    /// the ids the world holds.
    template <class Present>
    void check(const PairEvents& events, const std::vector<Pair>& now, Present present) {
        std::set<BoxId> replaced;
        for (const BoxId id : removed_)
            if (present(id)) replaced.insert(id);
        const auto renewed = [&](const Pair& p) {
            return cleared_ || replaced.count(p.a) != 0 || replaced.count(p.b) != 0;
        };
        std::vector<Pair> begun;
        for (const Pair& p : now)
            if (renewed(p) || !std::binary_search(previous_.begin(), previous_.end(), p)) begun.push_back(p);
        std::vector<Pair> ended;
        for (const Pair& p : previous_)
            if (renewed(p) || !std::binary_search(now.begin(), now.end(), p)) ended.push_back(p);
        const auto same = [](std::span<const Pair> got, const std::vector<Pair>& want) {
            return std::equal(got.begin(), got.end(), want.begin(), want.end());
        };
        if (!same(events.begun(), begun)) broken_promise("the begun pairs differ from the model");
        if (!same(events.ended(), ended)) broken_promise("the ended pairs differ from the model");
        previous_ = now;
        forget_removals();
    }

private:
    std::vector<Pair> previous_;
    std::set<BoxId> removed_;
    bool cleared_ = false;
};

/// Box queries (one and a batch) with the first few boxes the model holds, and rays from the
/// middle of the first ones, against brute force (smb::overlaps, smb::ray_entry).
template <std::floating_point Real, int Dim>
void check_queries(World<Real, Dim>& world, const std::map<BoxId, Box<Real, Dim>>& model) {
    using BoxT = Box<Real, Dim>;
    constexpr std::size_t kQueries = 3;
    std::vector<BoxT> queries;
    for (const auto& [id, box] : model) {
        if (queries.size() == kQueries) break;
        queries.push_back(box);
    }
    std::vector<QueryHit> want_hits;
    std::vector<BoxId> found;
    for (std::size_t q = 0; q < queries.size(); ++q) {
        std::vector<BoxId> want;
        for (const auto& [id, box] : model)
            if (overlaps(queries[q], box)) want.push_back(id);
        world.query(queries[q], found);
        std::sort(found.begin(), found.end());
        if (found != want) broken_promise("a box query differs from brute force");
        for (const BoxId id : want) want_hits.push_back({q, id});
    }
    std::vector<QueryHit> hits;
    world.query(std::span<const BoxT>(queries), hits);
    std::sort(hits.begin(), hits.end());
    if (hits != want_hits) broken_promise("a batch query differs from brute force");

    for (const BoxT& from : queries) {
        Ray<Real, Dim> ray;
        for (int k = 0; k < Dim; ++k) {
            ray.origin[k] = from.min[k] / 2 + from.max[k] / 2;
            ray.direction[k] = static_cast<Real>(k == 0 ? 1.0 : 0.5 - 0.75 * (k - 1));
        }
        if (!is_valid(ray)) continue;
        std::vector<RayHit<Real>> want;
        for (const auto& [id, box] : model)
            if (const std::optional<double> t = ray_entry(ray, box)) want.push_back({id, static_cast<Real>(*t)});
        std::sort(want.begin(), want.end(),
                  [](const RayHit<Real>& x, const RayHit<Real>& y) { return x.t != y.t ? x.t < y.t : x.id < y.id; });
        std::vector<RayHit<Real>> got;
        world.cast_ray(ray, RayHits::all, got);
        if (got != want) broken_promise("a ray cast (all hits) differs from brute force");
        world.cast_ray(ray, RayHits::nearest, got);
        if (want.size() > 1) want.resize(1);
        if (got != want) broken_promise("a ray cast (nearest) differs from brute force");
    }
}

}  // namespace smb::fuzz::world_ops_detail
