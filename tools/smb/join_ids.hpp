// SPDX-License-Identifier: MIT
#pragma once
// `smb join` follows two scenes in one World. Their ids are separate name spaces (id 7 of the
// left scene is not id 7 of the right one), so each side's ids are mapped to ids of one dense
// internal space; the internal id tells the side and the scene's own id back. Internal ids
// freed by removed boxes are reused, so the space stays as small as the scenes.

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "smb/pair.hpp"

namespace smb::io {

enum class JoinSide : std::uint8_t { left = 0, right = 1 };

class JoinIds {
public:
    /// A fresh internal id for `id` of `side`; `id` must not be mapped on that side.
    BoxId add(JoinSide side, BoxId id) {
        BoxId internal = 0;
        if (free_.empty()) {
            internal = static_cast<BoxId>(side_ids_.size());
            side_ids_.push_back({side, id});
        } else {
            internal = free_.back();
            free_.pop_back();
            side_ids_[internal] = {side, id};
        }
        map(side)[id] = internal;
        return internal;
    }

    /// The internal id of `id` of `side`, which must be mapped.
    [[nodiscard]] BoxId find(JoinSide side, BoxId id) const { return map(side).at(id); }

    /// Forgets `id` of `side` (which must be mapped) and returns its internal id, free again.
    BoxId release(JoinSide side, BoxId id) {
        auto& ids = map(side);
        const auto found = ids.find(id);
        const BoxId internal = found->second;
        ids.erase(found);
        free_.push_back(internal);
        return internal;
    }

    [[nodiscard]] JoinSide side(BoxId internal) const { return side_ids_[internal].side; }
    /// The scene's own id behind `internal`.
    [[nodiscard]] BoxId id(BoxId internal) const { return side_ids_[internal].id; }

    void clear() {
        maps_[0].clear();
        maps_[1].clear();
        side_ids_.clear();
        free_.clear();
    }

private:
    struct SideId {
        JoinSide side;
        BoxId id;
    };

    std::unordered_map<BoxId, BoxId>& map(JoinSide side) { return maps_[static_cast<int>(side)]; }
    [[nodiscard]] const std::unordered_map<BoxId, BoxId>& map(JoinSide side) const {
        return maps_[static_cast<int>(side)];
    }

    std::array<std::unordered_map<BoxId, BoxId>, 2> maps_;
    std::vector<SideId> side_ids_;
    std::vector<BoxId> free_;
};

}  // namespace smb::io
