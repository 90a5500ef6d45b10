// SPDX-License-Identifier: MIT
#pragma once
// A plain map of id -> box that mirrors every call a test makes on an smb::World, and the
// checks that the world agrees with it: same ids, same boxes, same pairs as brute force.

#include <gtest/gtest.h>

#include <cstddef>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "reference/brute_force.hpp"
#include "reference/pair_check.hpp"
#include "smb/world.hpp"

namespace smb::test {

template <std::floating_point Real, int Dim>
class ReferenceWorld {
public:
    using box_type = Box<Real, Dim>;

    void insert(BoxId id, const box_type& box) { boxes_[id] = box; }
    void update(BoxId id, const box_type& box) { boxes_.at(id) = box; }
    void remove(BoxId id) { boxes_.erase(id); }
    void clear() { boxes_.clear(); }
    void assign(std::span<const box_type> boxes) {
        boxes_.clear();
        for (std::size_t i = 0; i < boxes.size(); ++i) boxes_[static_cast<BoxId>(i)] = boxes[i];
    }

    [[nodiscard]] bool contains(BoxId id) const { return boxes_.contains(id); }
    [[nodiscard]] const box_type& box(BoxId id) const { return boxes_.at(id); }
    [[nodiscard]] std::size_t size() const { return boxes_.size(); }
    [[nodiscard]] const std::map<BoxId, box_type>& boxes() const { return boxes_; }

    [[nodiscard]] std::vector<BoxId> ids() const {
        std::vector<BoxId> out;
        out.reserve(boxes_.size());
        for (const auto& entry : boxes_) out.push_back(entry.first);
        return out;
    }

    [[nodiscard]] std::vector<Pair> pairs() const {
        std::vector<BoxId> ids;
        std::vector<box_type> boxes;
        ids.reserve(boxes_.size());
        boxes.reserve(boxes_.size());
        for (const auto& [id, box] : boxes_) {
            ids.push_back(id);
            boxes.push_back(box);
        }
        return brute_force_pairs<Real, Dim>(ids, boxes);
    }

    [[nodiscard]] BoxDescriber describer() const {
        return [this](BoxId id) {
            const auto it = boxes_.find(id);
            return it == boxes_.end() ? std::string("<not in the reference>") : describe(it->second);
        };
    }

private:
    std::map<BoxId, box_type> boxes_;
};

/// Success when `world` holds exactly the ids and boxes of `reference`.
template <std::floating_point Real, int Dim>
::testing::AssertionResult same_contents(const World<Real, Dim>& world, const ReferenceWorld<Real, Dim>& reference) {
    if (world.size() != reference.size()) {
        return ::testing::AssertionFailure()
               << "world holds " << world.size() << " boxes, reference " << reference.size();
    }
    for (const auto& [id, box] : reference.boxes()) {
        if (!world.contains(id)) return ::testing::AssertionFailure() << "world lacks id " << id;
        const auto stored = world.box(id);
        if (!(stored == box)) {
            return ::testing::AssertionFailure()
                   << "box " << id << " is " << describe(stored) << ", expected " << describe(box);
        }
    }
    return ::testing::AssertionSuccess();
}

/// Detects once and checks the pairs and the statistics against the reference.
template <std::floating_point Real, int Dim>
::testing::AssertionResult detects_like(World<Real, Dim>& world, const ReferenceWorld<Real, Dim>& reference) {
    std::vector<Pair> pairs;
    const DetectStats stats = world.detect(pairs);
    auto result = same_pairs(pairs, reference.pairs(), reference.describer());
    if (!result) return result;
    if (stats.pairs != pairs.size()) {
        return ::testing::AssertionFailure()
               << "DetectStats::pairs is " << stats.pairs << " but " << pairs.size() << " pairs were reported";
    }
    if (stats.boxes != reference.size()) {
        return ::testing::AssertionFailure()
               << "DetectStats::boxes is " << stats.boxes << ", expected " << reference.size();
    }
    return ::testing::AssertionSuccess();
}

/// Both checks above, the contents first.
template <std::floating_point Real, int Dim>
::testing::AssertionResult agrees_with(World<Real, Dim>& world, const ReferenceWorld<Real, Dim>& reference) {
    auto contents = same_contents(world, reference);
    if (!contents) return contents;
    return detects_like(world, reference);
}

}  // namespace smb::test
