// SPDX-License-Identifier: MIT
#pragma once
// One rank's share of the paper's dynamic environment: the rows of DynamicEnvironment whose id
// mod `parts` is `part`, the same boxes bit for bit, without ever storing the others. For
// `smb run --distributed`, where every rank generates its own share.

#include <array>
#include <cstddef>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"
#include "smb/workload/dynamic_environment.hpp"

namespace smb::workload {

/// The boxes of DynamicEnvironment<Dim>(params) whose id mod `parts` is `part`, step after step.
///
/// The serial environment draws every number from one std::mt19937_64 stream, box after box in
/// id order. A share follows the same stream: it draws the numbers of its own boxes and skips
/// (std::mt19937_64::discard, which never tempers the skipped numbers) those of the others, so
/// each step costs every share the stream's length, 2·Dim numbers per box of the whole scene,
/// but stores only its own boxes, each with its position in the global id order (which says how
/// far to skip). The deletions of a step, Λ·N at most, are drawn in full by every share: their
/// positions are the only global state a share holds, for the length of a step.
template <int Dim>
class EnvironmentShare {
public:
    static_assert(Dim == 2 || Dim == 3, "the environment is 2D or 3D");
    using box_type = Box<double, Dim>;

    /// Step 0's share. Throws std::invalid_argument as DynamicEnvironment does, or when `part`
    /// is not in [0, parts).
    EnvironmentShare(const EnvironmentParams& params, int part, int parts);

    /// Advances by one step, as DynamicEnvironment::step().
    void step();

    /// This share's ids and boxes, in increasing id order.
    [[nodiscard]] std::span<const BoxId> ids() const noexcept { return ids_; }
    [[nodiscard]] std::span<const box_type> boxes() const noexcept { return boxes_; }
    /// The number of boxes of the whole scene.
    [[nodiscard]] std::size_t global_size() const noexcept { return global_size_; }
    [[nodiscard]] std::size_t step_index() const noexcept { return step_index_; }
    [[nodiscard]] double cube_side() const noexcept { return cube_side_; }
    [[nodiscard]] double packing_density() const noexcept { return packing_density_; }
    /// Bytes of the share's arrays (their capacity).
    [[nodiscard]] std::size_t bytes_held() const noexcept;

private:
    /// The engine of the serial environment, with the skipped numbers discarded in one call
    /// when the next number is drawn.
    class SkippingEngine {
    public:
        using result_type = std::mt19937_64::result_type;
        explicit SkippingEngine(std::uint64_t seed) : engine_(seed) {}
        void skip(unsigned long long count) noexcept { pending_ += count; }
        result_type operator()() {
            if (pending_ > 0) engine_.discard(pending_);
            pending_ = 0;
            return engine_();
        }

    private:
        std::mt19937_64 engine_;
        unsigned long long pending_ = 0;
    };

    void place_new_boxes(std::size_t count);
    void delete_random_boxes(std::size_t count);
    void move_boxes(std::size_t survivors);
    void refresh_box(std::size_t row);
    [[nodiscard]] bool is_mine(BoxId id) const noexcept { return id % parts_ == part_; }

    EnvironmentParams params_;
    BoxId part_ = 0;
    BoxId parts_ = 1;
    double cube_side_ = 0;
    double min_side_ = 0;
    double max_side_ = 1;
    double packing_density_ = 0;
    SkippingEngine rng_;
    std::size_t step_index_ = 0;
    std::size_t global_size_ = 0;
    BoxId next_id_ = 0;

    std::vector<BoxId> ids_;
    std::vector<std::size_t> positions_;  ///< each row's index in the whole scene's id order
    std::vector<std::array<double, Dim>> centres_;
    std::vector<std::array<double, Dim>> sides_;
    std::vector<box_type> boxes_;
    std::vector<std::size_t> drawn_;  ///< a step's drawn positions (doomed or spared), sorted
};

}  // namespace smb::workload
