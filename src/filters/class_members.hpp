// SPDX-License-Identifier: MIT
#pragma once
// The interaction class of each position (of a World's list of moving boxes, or of a
// Detector's array) and each class's members in an order kept from one detection to the next: a
// member that leaves is swap-removed, one that joins is appended. A class's engine then finds
// the same box at the same index; an order derived from the positions would shift every member
// past one that left, and the persistent cuts would find no box where they left it.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace smb::detail {

class ClassMembers {
public:
    static constexpr std::uint8_t kNone = 0xFF;

    /// `count` empty classes and no positions.
    void reset(std::size_t count) {
        members_.clear();
        members_.resize(count);
        class_of_.clear();
        index_.clear();
    }
    void clear() {
        std::vector<std::vector<std::uint32_t>>().swap(members_);
        std::vector<std::uint8_t>().swap(class_of_);
        std::vector<std::uint32_t>().swap(index_);
    }

    [[nodiscard]] std::span<const std::uint32_t> members(std::size_t c) const noexcept { return members_[c]; }
    [[nodiscard]] std::uint8_t class_of(std::size_t p) const noexcept { return class_of_[p]; }

    /// `size` positions: those past it leave their classes, new ones are in none.
    void resize(std::size_t size) {
        for (std::size_t p = size; p < class_of_.size(); ++p) leave(p);
        class_of_.resize(size, kNone);
        index_.resize(size, 0);
    }
    /// Position p is now of class c (kNone: of none), taking the next index there if it changed.
    void move(std::size_t p, std::uint8_t c) {
        if (p >= class_of_.size()) resize(p + 1);
        if (class_of_[p] == c) return;
        leave(p);
        if (c == kNone) return;
        std::vector<std::uint32_t>& members = members_[c];
        class_of_[p] = c;
        index_[p] = static_cast<std::uint32_t>(members.size());
        members.push_back(static_cast<std::uint32_t>(p));
    }
    /// The positions were swap-removed at p: the one at `last` (the last) now sits at p.
    void swap_remove(std::size_t p, std::size_t last) {
        leave(p);
        const std::uint8_t c = class_of_[last];
        if (p != last && c != kNone) {
            members_[c][index_[last]] = static_cast<std::uint32_t>(p);
            class_of_[p] = c;
            index_[p] = index_[last];
        }
        class_of_.pop_back();
        index_.pop_back();
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        std::size_t bytes = members_.capacity() * sizeof(std::vector<std::uint32_t>) + class_of_.capacity() +
                            index_.capacity() * sizeof(std::uint32_t);
        for (const auto& members : members_) bytes += members.capacity() * sizeof(std::uint32_t);
        return bytes;
    }

private:
    void leave(std::size_t p) {
        const std::uint8_t c = class_of_[p];
        if (c == kNone) return;
        std::vector<std::uint32_t>& members = members_[c];
        const std::uint32_t k = index_[p];
        const std::uint32_t moved = members.back();
        members[k] = moved;
        index_[moved] = k;
        members.pop_back();
        class_of_[p] = kNone;
    }

    std::vector<std::vector<std::uint32_t>> members_;
    std::vector<std::uint8_t> class_of_;  // per position; kNone where in no class
    std::vector<std::uint32_t> index_;    // per position, its index among its class's members
};

}  // namespace smb::detail
