// SPDX-License-Identifier: MIT
#pragma once
// The motion rules of the paper's Section 4 applied to any initial placement, for the scenes the
// paper has no generator for (clustered, mixed sizes, ...). Per step, with λ, λ_i uniform in
// (-Λ, Λ): the count changes by round(λ N) (random deletions, or new boxes placed as at step 0),
// every side l' = l + λ_i b and every centre c' = c + λ_i x (x: the domain's side on that axis).
// Sides reflect into the box's own size range and centres into the domain (a cube unless the
// family says otherwise), as smb::workload does for the paper's environment, so the only
// difference between scenes is where the boxes start and how large they are.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "scenes/scene.hpp"

namespace smb::bench {

/// A box as a placement draws it: centre, sides, and the range its sides stay in: side k in
/// [side_min, side_max] times stretch[k].
template <int Dim>
struct PlacedBox {
    std::array<double, Dim> centre{};
    std::array<double, Dim> sides{};
    double side_min = 0;
    double side_max = 1;
    std::array<double, Dim> stretch = filled(1.0);

    static constexpr std::array<double, Dim> filled(double value) {
        std::array<double, Dim> values{};
        values.fill(value);
        return values;
    }
};

template <int Dim>
class MovingBoxes final : public Scene<Dim> {
public:
    using Placement = std::function<PlacedBox<Dim>(std::mt19937_64&)>;

    /// `largest_side` is the paper's b: the scale of the per-step side change.
    MovingBoxes(std::size_t count, double cube_side, double largest_side, double update_factor, std::uint64_t seed,
                Placement place)
        : MovingBoxes(count, PlacedBox<Dim>::filled(cube_side), largest_side, update_factor, seed, std::move(place)) {}

    /// The same in a box of sides `domain` instead of a cube: centres move by λ_i times the side
    /// of their axis.
    MovingBoxes(std::size_t count, const std::array<double, Dim>& domain, double largest_side, double update_factor,
                std::uint64_t seed, Placement place)
        : count_(count),
          domain_(domain),
          largest_side_(largest_side),
          update_factor_(update_factor),
          rng_(seed),
          place_(std::move(place)) {}

    const SceneStep<Dim>& advance() override {
        removed_ids_.clear();
        std::size_t first_inserted = 0;
        if (!started_) {
            started_ = true;
            append_new(count_);
        } else {
            std::uniform_real_distribution<double> fraction(-update_factor_, update_factor_);
            const double change = std::round(fraction(rng_) * static_cast<double>(ids_.size()));
            if (change < 0) delete_random(static_cast<std::size_t>(-change));
            move_all(fraction);
            first_inserted = ids_.size();
            if (change > 0) append_new(static_cast<std::size_t>(change));
            ++step_.index;
        }
        refresh_boxes();
        step_.ids = ids_;
        step_.boxes = boxes_;
        step_.removed_ids = removed_ids_;
        step_.first_inserted = first_inserted;
        return step_;
    }

private:
    void append_new(std::size_t count) {
        for (std::size_t i = 0; i < count; ++i) {
            PlacedBox<Dim> placed = place_(rng_);
            for (int k = 0; k < Dim; ++k) placed.centre[k] = keep_inside(placed.centre[k], placed.sides[k], k);
            ids_.push_back(next_id_++);
            placed_.push_back(placed);
        }
    }

    // Stable compaction keeps ids increasing, so survivors stay in the same relative order.
    void delete_random(std::size_t count) {
        count = std::min(count, ids_.size());
        std::vector<std::uint8_t> doomed(ids_.size(), 0);
        std::uniform_int_distribution<std::size_t> pick(0, ids_.size() - 1);
        for (std::size_t chosen = 0; chosen < count;) {
            const std::size_t i = pick(rng_);
            if (!doomed[i]) {
                doomed[i] = 1;
                ++chosen;
            }
        }
        std::size_t kept = 0;
        for (std::size_t i = 0; i < ids_.size(); ++i) {
            if (doomed[i]) {
                removed_ids_.push_back(ids_[i]);
                continue;
            }
            ids_[kept] = ids_[i];
            placed_[kept] = placed_[i];
            ++kept;
        }
        ids_.resize(kept);
        placed_.resize(kept);
    }

    void move_all(std::uniform_real_distribution<double>& fraction) {
        for (PlacedBox<Dim>& box : placed_) {
            for (int k = 0; k < Dim; ++k) {
                box.sides[k] = reflect(box.sides[k] + fraction(rng_) * largest_side_, box.side_min * box.stretch[k],
                                       box.side_max * box.stretch[k]);
            }
            for (int k = 0; k < Dim; ++k) {
                box.centre[k] = keep_inside(box.centre[k] + fraction(rng_) * domain_[k], box.sides[k], k);
            }
        }
    }

    [[nodiscard]] double keep_inside(double centre, double side, int axis) const {
        const double half = 0.5 * side;
        return reflect(centre, half, std::max(half, domain_[axis] - half));
    }

    static double reflect(double value, double low, double high) {
        if (value < low) value = 2 * low - value;
        if (value > high) value = 2 * high - value;
        return std::clamp(value, low, high);
    }

    void refresh_boxes() {
        boxes_.resize(placed_.size());
        for (std::size_t i = 0; i < placed_.size(); ++i) {
            for (int k = 0; k < Dim; ++k) {
                const double half = 0.5 * placed_[i].sides[k];
                boxes_[i].min[k] = static_cast<float>(placed_[i].centre[k] - half);
                boxes_[i].max[k] = static_cast<float>(placed_[i].centre[k] + half);
            }
        }
    }

    std::size_t count_;
    std::array<double, Dim> domain_;
    double largest_side_;
    double update_factor_;
    std::mt19937_64 rng_;
    Placement place_;
    bool started_ = false;
    BoxId next_id_ = 0;
    std::vector<BoxId> ids_;
    std::vector<PlacedBox<Dim>> placed_;
    std::vector<BenchBox<Dim>> boxes_;
    std::vector<BoxId> removed_ids_;
    SceneStep<Dim> step_;
};

}  // namespace smb::bench
