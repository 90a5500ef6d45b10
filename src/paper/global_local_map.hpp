// SPDX-License-Identifier: MIT
#pragma once
// The global-local map of the paper's Section 2.4 (7): inside one cell, each box gets a small
// local number (order of first appearance in the cell's list of the deepest axis), so that the
// cell's pair flags fit an m x m matrix instead of the N x N matrix of I-COLLIDE. The map is
// indexed by box slot and is reset after each cell by walking the cell's boxes again, so its
// cost per cell is the cell's size, not N.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace smb::detail {

class GlobalLocalMap {
public:
    static constexpr std::uint32_t kAbsent = ~std::uint32_t{0};

    void reset(std::size_t boxes) {
        local_of_.assign(boxes, kAbsent);
        global_of_.clear();
    }

    /// The local number of `box`, assigning the next one if it is new in this cell.
    std::uint32_t local(std::uint32_t box) {
        std::uint32_t& local = local_of_[box];
        if (local == kAbsent) {
            local = static_cast<std::uint32_t>(global_of_.size());
            global_of_.push_back(box);
        }
        return local;
    }
    [[nodiscard]] std::uint32_t find(std::uint32_t box) const noexcept { return local_of_[box]; }
    [[nodiscard]] std::uint32_t global(std::uint32_t local) const noexcept { return global_of_[local]; }
    [[nodiscard]] std::size_t size() const noexcept { return global_of_.size(); }
    [[nodiscard]] const std::vector<std::uint32_t>& boxes() const noexcept { return global_of_; }

    /// Forgets the current cell.
    void clear_cell() noexcept {
        for (const std::uint32_t box : global_of_) local_of_[box] = kAbsent;
        global_of_.clear();
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return (local_of_.capacity() + global_of_.capacity()) * sizeof(std::uint32_t);
    }

private:
    std::vector<std::uint32_t> local_of_;
    std::vector<std::uint32_t> global_of_;
};

}  // namespace smb::detail
