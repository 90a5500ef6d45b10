// SPDX-License-Identifier: MIT
#pragma once
// The artificial dynamic environment of Li, Feng & Owen (2006), Section 4: boxes placed at random
// in a cube that every step move, resize, appear and disappear by a random fraction of an
// "update factor". One seeded implementation serves `smb run`, `smb generate`, the tests and the
// benchmarks, so the same parameters always give the same scene on every platform.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::workload {

/// Parameters in the paper's notation. The largest side is b = 1 and the smallest a = b / H.
struct EnvironmentParams {
    std::size_t box_count = 200000;   ///< N at step 0
    double packing_density = 0.4;     ///< E = N ((a + b) / 2)^Dim / x^Dim; sets x when cube_side is empty
    std::optional<double> cube_side;  ///< x; when given, E is derived from it instead
    double size_ratio = 2.5;          ///< H = b / a, at least 1
    double update_factor = 1e-3;      ///< Λ in [0, 1): bound of every random fraction λ, λ_i
    std::uint64_t seed = 1;           ///< seed of the std::mt19937_64 that drives everything
};

/// Side x of the cube that holds `box_count` boxes of mean side (a + b) / 2 at density E.
[[nodiscard]] double cube_side_for_density(std::size_t box_count, double packing_density, double min_side,
                                           double max_side, int dim);
/// Density E of `box_count` boxes of mean side (a + b) / 2 in a cube of side x.
[[nodiscard]] double density_for_cube_side(std::size_t box_count, double cube_side, double min_side, double max_side,
                                           int dim);

/// What one step changed. The spans point into the environment's current arrays and stay valid
/// until the next call of DynamicEnvironment::step().
template <int Dim>
struct StepChanges {
    using box_type = Box<double, Dim>;

    std::span<const BoxId> removed_ids;
    std::span<const BoxId> updated_ids;  ///< every surviving box: they all move every step
    std::span<const box_type> updated_boxes;
    std::span<const BoxId> inserted_ids;  ///< fresh ids, larger than every id used before
    std::span<const box_type> inserted_boxes;
};

/// The environment. Step 0 is the initial placement; each call of step() advances by one step.
///
/// Rules of a step, with λ, λ_i drawn uniformly from the open interval (-Λ, Λ):
///  - the count changes by round(λ N) (half away from zero): that many distinct random boxes
///    are deleted, or that many new boxes are placed as at step 0 under fresh ids;
///  - every surviving box moves and resizes: each side l' = l + λ_i b, then each centre
///    coordinate c' = c + λ_i x, every λ_i drawn independently per box and axis.
/// Boundaries reflect: a side that leaves [a, b] is mirrored back at the bound it crossed, and a
/// centre is mirrored at the nearest position that keeps the whole box inside [0, x]^Dim (then
/// both are clamped, which matters only when a step is larger than the room to move). So every
/// box is always valid, has sides in [a, b] and lies inside the cube.
///
/// Ids count up from 0 and are never reused. The current arrays are kept in increasing id order.
template <int Dim>
class DynamicEnvironment {
public:
    static_assert(Dim == 2 || Dim == 3, "the environment is 2D or 3D");
    using box_type = Box<double, Dim>;

    /// Places the boxes of step 0. Throws std::invalid_argument on parameters out of range
    /// (E <= 0, H < 1, Λ outside [0, 1), a cube smaller than the largest box).
    explicit DynamicEnvironment(const EnvironmentParams& params);

    /// Advances by one step and returns what changed.
    const StepChanges<Dim>& step();

    /// What the last step changed; before the first step(), step 0 as all boxes inserted.
    [[nodiscard]] const StepChanges<Dim>& changes() const noexcept { return changes_; }

    [[nodiscard]] std::span<const BoxId> ids() const noexcept { return ids_; }
    [[nodiscard]] std::span<const box_type> boxes() const noexcept { return boxes_; }
    [[nodiscard]] std::size_t size() const noexcept { return ids_.size(); }
    /// Number of steps taken since step 0.
    [[nodiscard]] std::size_t step_index() const noexcept { return step_index_; }

    [[nodiscard]] double cube_side() const noexcept { return cube_side_; }
    [[nodiscard]] double min_side() const noexcept { return min_side_; }
    [[nodiscard]] double max_side() const noexcept { return max_side_; }
    /// E of step 0, as defined by the paper (from N, a, b and x, not from the drawn sides).
    [[nodiscard]] double packing_density() const noexcept { return packing_density_; }
    [[nodiscard]] const EnvironmentParams& params() const noexcept { return params_; }

private:
    void place_new_boxes(std::size_t count);
    void delete_random_boxes(std::size_t count);
    void move_boxes(std::size_t count);
    void refresh_boxes(std::size_t first);
    void publish_changes(std::size_t survivors);

    EnvironmentParams params_;
    double cube_side_ = 0;
    double min_side_ = 0;
    double max_side_ = 1;
    double packing_density_ = 0;
    std::mt19937_64 rng_;
    std::size_t step_index_ = 0;
    BoxId next_id_ = 0;

    // Centres and sides are the state; boxes_ is derived from them so that repeated motion never
    // accumulates rounding in the side lengths.
    std::vector<BoxId> ids_;
    std::vector<std::array<double, Dim>> centres_;
    std::vector<std::array<double, Dim>> sides_;
    std::vector<box_type> boxes_;
    std::vector<BoxId> removed_ids_;
    std::vector<std::uint8_t> doomed_;
    StepChanges<Dim> changes_;
};

}  // namespace smb::workload
