// SPDX-License-Identifier: MIT
// The split of a frame into removals, updates and insertions that `smb pairs` feeds to World.

#include <gtest/gtest.h>

#include <vector>

#include "frame_diff.hpp"

namespace smb::io {
namespace {

SceneFrame<2> frame_with(const std::vector<BoxId>& ids) {
    SceneFrame<2> frame;
    for (const BoxId id : ids) {
        frame.ids.push_back(id);
        const double x = static_cast<double>(id);
        frame.boxes.push_back({{x, 0}, {x + 1, 1}});
    }
    return frame;
}

TEST(FrameDiff, SplitsIntoRemovedUpdatedInserted) {
    const std::vector<BoxId> previous{1, 3, 5, 7};
    FrameChanges<2> changes;
    diff_frames<2>(previous, frame_with({0, 3, 4, 7, 9}), changes);
    EXPECT_EQ(changes.removed_ids, (std::vector<BoxId>{1, 5}));
    EXPECT_EQ(changes.updated_ids, (std::vector<BoxId>{3, 7}));
    EXPECT_EQ(changes.inserted_ids, (std::vector<BoxId>{0, 4, 9}));
    ASSERT_EQ(changes.inserted_boxes.size(), 3u);
    EXPECT_EQ(changes.inserted_boxes[1].min[0], 4.0);
    EXPECT_EQ(changes.updated_boxes[1].min[0], 7.0);
}

TEST(FrameDiff, EmptySides) {
    FrameChanges<2> changes;
    diff_frames<2>({}, frame_with({2, 8}), changes);
    EXPECT_EQ(changes.inserted_ids, (std::vector<BoxId>{2, 8}));
    EXPECT_TRUE(changes.removed_ids.empty());

    const std::vector<BoxId> previous{2, 8};
    diff_frames<2>(previous, frame_with({}), changes);
    EXPECT_EQ(changes.removed_ids, (std::vector<BoxId>{2, 8}));
    EXPECT_TRUE(changes.inserted_ids.empty());
    EXPECT_TRUE(changes.updated_ids.empty());
}

}  // namespace
}  // namespace smb::io
