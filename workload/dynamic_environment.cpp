// SPDX-License-Identifier: MIT
#include "smb/workload/dynamic_environment.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>

#include "environment_draws.hpp"
#include "environment_shape.hpp"

namespace smb::workload {

using draws::reflect_into;
using draws::symmetric_unit;
using draws::uniform_between;
using draws::uniform_index;

namespace {

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

EnvironmentShape environment_shape(const EnvironmentParams& params, int dim) {
    require(std::isfinite(params.size_ratio) && params.size_ratio >= 1, "the size ratio H must be at least 1");
    require(std::isfinite(params.update_factor) && params.update_factor >= 0 && params.update_factor < 1,
            "the update factor must lie in [0, 1)");
    EnvironmentShape shape;
    shape.max_side = 1;
    shape.min_side = shape.max_side / params.size_ratio;
    if (params.cube_side) {
        shape.cube_side = *params.cube_side;
        require(std::isfinite(shape.cube_side), "the cube side must be finite");
        shape.packing_density =
            density_for_cube_side(params.box_count, shape.cube_side, shape.min_side, shape.max_side, dim);
    } else {
        require(std::isfinite(params.packing_density) && params.packing_density > 0,
                "the packing density E must be positive");
        shape.packing_density = params.packing_density;
        shape.cube_side =
            cube_side_for_density(params.box_count, shape.packing_density, shape.min_side, shape.max_side, dim);
    }
    require(shape.cube_side >= shape.max_side, "the cube side x = " + shortest_number(shape.cube_side) +
                                                   " is smaller than the largest box side b = 1 (lower E or raise N)");
    return shape;
}

template <int Dim>
DynamicEnvironment<Dim>::DynamicEnvironment(const EnvironmentParams& params) : params_(params), rng_(params.seed) {
    const EnvironmentShape shape = environment_shape(params, Dim);
    cube_side_ = shape.cube_side;
    min_side_ = shape.min_side;
    max_side_ = shape.max_side;
    packing_density_ = shape.packing_density;
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
    for (std::size_t i = first; i < ids_.size(); ++i) boxes_[i] = box_in_cube<Dim>(centres_[i], sides_[i], cube_side_);
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
