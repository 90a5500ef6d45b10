// SPDX-License-Identifier: MIT
#include "smb/workload/environment_share.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

#include "environment_draws.hpp"
#include "environment_shape.hpp"

namespace smb::workload {

template <int Dim>
EnvironmentShare<Dim>::EnvironmentShare(const EnvironmentParams& params, int part, int parts)
    : params_(params), rng_(params.seed) {
    if (parts < 1 || part < 0 || part >= parts) {
        throw std::invalid_argument("environment share: the part must lie in [0, parts) and parts be at least 1");
    }
    part_ = static_cast<BoxId>(part);
    parts_ = static_cast<BoxId>(parts);
    const EnvironmentShape shape = environment_shape(params, Dim);
    cube_side_ = shape.cube_side;
    min_side_ = shape.min_side;
    max_side_ = shape.max_side;
    packing_density_ = shape.packing_density;
    place_new_boxes(params.box_count);
}

template <int Dim>
void EnvironmentShare<Dim>::step() {
    // The order of DynamicEnvironment::step(): λ, the deletions, the motion, the insertions.
    const double lambda = params_.update_factor * draws::symmetric_unit(rng_);
    const auto count_change = std::llround(lambda * static_cast<double>(global_size_));
    if (count_change < 0) delete_random_boxes(static_cast<std::size_t>(-count_change));
    move_boxes(global_size_);
    if (count_change > 0) place_new_boxes(static_cast<std::size_t>(count_change));
    ++step_index_;
}

template <int Dim>
void EnvironmentShare<Dim>::place_new_boxes(std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) {
        const BoxId id = next_id_++;
        if (!is_mine(id)) {
            rng_.skip(draws::per_box(Dim));
            continue;
        }
        std::array<double, Dim> centre{};
        std::array<double, Dim> side{};
        for (int k = 0; k < Dim; ++k) {
            side[k] = draws::uniform_between(rng_, min_side_, max_side_);
            centre[k] = draws::uniform_between(rng_, side[k] / 2, cube_side_ - side[k] / 2);
        }
        ids_.push_back(id);
        positions_.push_back(global_size_ + i);
        centres_.push_back(centre);
        sides_.push_back(side);
        boxes_.emplace_back();
        refresh_box(ids_.size() - 1);
    }
    global_size_ += count;
}

template <int Dim>
void EnvironmentShare<Dim>::delete_random_boxes(std::size_t count) {
    const std::size_t n = global_size_;
    count = std::min(count, n);
    // The serial draw: whichever of the doomed or the spared set is smaller, a repeated position
    // drawn again. Only the set of drawn positions matters, which every share draws in full.
    const bool draw_doomed = count <= n / 2;
    const std::size_t to_draw = draw_doomed ? count : n - count;
    std::unordered_set<std::size_t> seen;
    seen.reserve(to_draw);
    drawn_.clear();
    while (drawn_.size() < to_draw) {
        const std::size_t position = draws::uniform_index(rng_, n);
        if (seen.insert(position).second) drawn_.push_back(position);
    }
    std::sort(drawn_.begin(), drawn_.end());

    std::size_t kept = 0;
    std::size_t drawn_below = 0;  // drawn positions below the row's, rows being in position order
    for (std::size_t row = 0; row < ids_.size(); ++row) {
        const std::size_t position = positions_[row];
        while (drawn_below < drawn_.size() && drawn_[drawn_below] < position) ++drawn_below;
        const bool drawn = drawn_below < drawn_.size() && drawn_[drawn_below] == position;
        if (drawn == draw_doomed) continue;
        const std::size_t doomed_below = draw_doomed ? drawn_below : position - drawn_below;
        ids_[kept] = ids_[row];
        positions_[kept] = position - doomed_below;
        centres_[kept] = centres_[row];
        sides_[kept] = sides_[row];
        boxes_[kept] = boxes_[row];
        ++kept;
    }
    ids_.resize(kept);
    positions_.resize(kept);
    centres_.resize(kept);
    sides_.resize(kept);
    boxes_.resize(kept);
    drawn_.clear();
    global_size_ = n - count;
}

template <int Dim>
void EnvironmentShare<Dim>::move_boxes(std::size_t survivors) {
    const double x = cube_side_;
    const double b = max_side_;
    std::size_t next_position = 0;
    for (std::size_t row = 0; row < ids_.size(); ++row) {
        rng_.skip(draws::per_box(Dim) * (positions_[row] - next_position));
        auto& centre = centres_[row];
        auto& side = sides_[row];
        for (int k = 0; k < Dim; ++k) {
            const double side_fraction = params_.update_factor * draws::symmetric_unit(rng_);
            const double centre_fraction = params_.update_factor * draws::symmetric_unit(rng_);
            side[k] = draws::reflect_into(side[k] + side_fraction * b, min_side_, max_side_);
            centre[k] = draws::reflect_into(centre[k] + centre_fraction * x, side[k] / 2, x - side[k] / 2);
        }
        refresh_box(row);
        next_position = positions_[row] + 1;
    }
    rng_.skip(draws::per_box(Dim) * (survivors - next_position));
}

template <int Dim>
void EnvironmentShare<Dim>::refresh_box(std::size_t row) {
    boxes_[row] = box_in_cube<Dim>(centres_[row], sides_[row], cube_side_);
}

template <int Dim>
std::size_t EnvironmentShare<Dim>::bytes_held() const noexcept {
    return ids_.capacity() * sizeof(BoxId) + positions_.capacity() * sizeof(std::size_t) +
           centres_.capacity() * sizeof(centres_[0]) + sides_.capacity() * sizeof(sides_[0]) +
           boxes_.capacity() * sizeof(box_type) + drawn_.capacity() * sizeof(std::size_t);
}

template class EnvironmentShare<2>;
template class EnvironmentShare<3>;

}  // namespace smb::workload
