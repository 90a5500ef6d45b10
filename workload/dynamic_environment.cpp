// SPDX-License-Identifier: MIT
#include "smb/workload/dynamic_environment.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>

namespace smb::workload {

namespace {

// The draws below use only the raw 64-bit output of the engine, never the standard
// distributions: those are implementation-defined, and a scene must be the same everywhere.

constexpr double two_pow_minus_52 = 0x1.0p-52;
constexpr double two_pow_minus_53 = 0x1.0p-53;

/// Uniform in [0, 1).
double unit_interval(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * two_pow_minus_53; }

/// Uniform in the open interval (-1, 1), symmetric about 0: the odd multiples of 2^-52 in
/// (-1, 1) are all exactly representable, so no rounding can reach either bound.
double symmetric_unit(std::mt19937_64& rng) {
    const auto k = static_cast<std::int64_t>(rng() >> 12);  // [0, 2^52)
    const std::int64_t odd = 2 * k + 1 - (std::int64_t{1} << 52);
    return static_cast<double>(odd) * two_pow_minus_52;
}

/// Uniform index in [0, count), by the multiply-high reduction (bias below 2^-40 here).
std::size_t uniform_index(std::mt19937_64& rng, std::size_t count) {
    __extension__ using wide = unsigned __int128;
    return static_cast<std::size_t>((static_cast<wide>(rng()) * count) >> 64);
}

double uniform_between(std::mt19937_64& rng, double low, double high) {
    return std::min(high, low + (high - low) * unit_interval(rng));
}

/// Mirrors `value` back into [low, high] at the bound it crossed; the clamp only acts when the
/// overshoot is larger than the interval itself.
double reflect_into(double value, double low, double high) {
    if (value < low) value = low + (low - value);
    if (value > high) value = high - (value - high);
    return std::clamp(value, low, high);
}

/// The shortest text that reads back to `value` (0.5, not 0.500000).
std::string shortest_number(double value) {
    char text[64];
    return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

void require(bool condition, const std::string& message) {
    if (!condition) throw std::invalid_argument("dynamic environment: " + message);
}

}  // namespace

double cube_side_for_density(std::size_t box_count, double packing_density, double min_side, double max_side, int dim) {
    const double mean_side = (min_side + max_side) / 2;
    return mean_side * std::pow(static_cast<double>(box_count) / packing_density, 1.0 / dim);
}

double density_for_cube_side(std::size_t box_count, double cube_side, double min_side, double max_side, int dim) {
    const double mean_side = (min_side + max_side) / 2;
    return static_cast<double>(box_count) * std::pow(mean_side / cube_side, dim);
}

template <int Dim>
DynamicEnvironment<Dim>::DynamicEnvironment(const EnvironmentParams& params) : params_(params), rng_(params.seed) {
    require(std::isfinite(params.size_ratio) && params.size_ratio >= 1, "the size ratio H must be at least 1");
    require(std::isfinite(params.update_factor) && params.update_factor >= 0 && params.update_factor < 1,
            "the update factor must lie in [0, 1)");
    max_side_ = 1;
    min_side_ = max_side_ / params.size_ratio;
    if (params.cube_side) {
        cube_side_ = *params.cube_side;
        require(std::isfinite(cube_side_), "the cube side must be finite");
        packing_density_ = density_for_cube_side(params.box_count, cube_side_, min_side_, max_side_, Dim);
    } else {
        require(std::isfinite(params.packing_density) && params.packing_density > 0,
                "the packing density E must be positive");
        packing_density_ = params.packing_density;
        cube_side_ = cube_side_for_density(params.box_count, packing_density_, min_side_, max_side_, Dim);
    }
    require(cube_side_ >= max_side_, "the cube side x = " + shortest_number(cube_side_) +
                                         " is smaller than the largest box side b = 1 (lower E or raise N)");

    place_new_boxes(params.box_count);
    publish_changes(0);
}

template <int Dim>
const StepChanges<Dim>& DynamicEnvironment<Dim>::step() {
    const double lambda = params_.update_factor * symmetric_unit(rng_);
    const auto count_change = std::llround(lambda * static_cast<double>(ids_.size()));

    removed_ids_.clear();
    if (count_change < 0) delete_random_boxes(static_cast<std::size_t>(-count_change));
    const std::size_t survivors = ids_.size();
    move_boxes(survivors);
    if (count_change > 0) place_new_boxes(static_cast<std::size_t>(count_change));

    ++step_index_;
    publish_changes(survivors);
    return changes_;
}

template <int Dim>
void DynamicEnvironment<Dim>::place_new_boxes(std::size_t count) {
    const std::size_t first = ids_.size();
    ids_.reserve(first + count);
    centres_.reserve(first + count);
    sides_.reserve(first + count);
    for (std::size_t i = 0; i < count; ++i) {
        std::array<double, Dim> centre{};
        std::array<double, Dim> side{};
        for (int k = 0; k < Dim; ++k) {
            side[k] = uniform_between(rng_, min_side_, max_side_);
            centre[k] = uniform_between(rng_, side[k] / 2, cube_side_ - side[k] / 2);
        }
        ids_.push_back(next_id_++);
        centres_.push_back(centre);
        sides_.push_back(side);
    }
    refresh_boxes(first);
}

template <int Dim>
void DynamicEnvironment<Dim>::delete_random_boxes(std::size_t count) {
    const std::size_t n = ids_.size();
    count = std::min(count, n);
    // Draw whichever of the doomed or the spared set is smaller, so that rejection of repeated
    // draws stays cheap even when most boxes go.
    const bool draw_doomed = count <= n / 2;
    const std::size_t to_draw = draw_doomed ? count : n - count;
    doomed_.assign(n, draw_doomed ? 0 : 1);
    for (std::size_t drawn = 0; drawn < to_draw;) {
        auto& mark = doomed_[uniform_index(rng_, n)];
        if (mark == (draw_doomed ? 0 : 1)) {
            mark = draw_doomed ? 1 : 0;
            ++drawn;
        }
    }

    // Stable compaction keeps the arrays in increasing id order.
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (doomed_[i]) {
            removed_ids_.push_back(ids_[i]);
            continue;
        }
        ids_[kept] = ids_[i];
        centres_[kept] = centres_[i];
        sides_[kept] = sides_[i];
        ++kept;
    }
    ids_.resize(kept);
    centres_.resize(kept);
    sides_.resize(kept);
    boxes_.resize(kept);
}

template <int Dim>
void DynamicEnvironment<Dim>::move_boxes(std::size_t count) {
    const double x = cube_side_;
    const double b = max_side_;
    for (std::size_t i = 0; i < count; ++i) {
        auto& centre = centres_[i];
        auto& side = sides_[i];
        for (int k = 0; k < Dim; ++k) {
            const double side_fraction = params_.update_factor * symmetric_unit(rng_);
            const double centre_fraction = params_.update_factor * symmetric_unit(rng_);
            side[k] = reflect_into(side[k] + side_fraction * b, min_side_, max_side_);
            centre[k] = reflect_into(centre[k] + centre_fraction * x, side[k] / 2, x - side[k] / 2);
        }
    }
    refresh_boxes(0);
}

template <int Dim>
void DynamicEnvironment<Dim>::refresh_boxes(std::size_t first) {
    boxes_.resize(ids_.size());
    for (std::size_t i = first; i < ids_.size(); ++i) {
        auto& box = boxes_[i];
        for (int k = 0; k < Dim; ++k) {
            const double half = sides_[i][k] / 2;
            // The clamps absorb the last-bit rounding of centre +- half at the cube's walls.
            box.min[k] = std::max(0.0, centres_[i][k] - half);
            box.max[k] = std::min(cube_side_, centres_[i][k] + half);
        }
    }
}

template <int Dim>
void DynamicEnvironment<Dim>::publish_changes(std::size_t survivors) {
    const std::span<const BoxId> ids(ids_);
    const std::span<const box_type> boxes(boxes_);
    changes_.removed_ids = removed_ids_;
    changes_.updated_ids = ids.first(survivors);
    changes_.updated_boxes = boxes.first(survivors);
    changes_.inserted_ids = ids.subspan(survivors);
    changes_.inserted_boxes = boxes.subspan(survivors);
}

template class DynamicEnvironment<2>;
template class DynamicEnvironment<3>;

}  // namespace smb::workload
