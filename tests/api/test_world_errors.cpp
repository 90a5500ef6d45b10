// SPDX-License-Identifier: MIT
// Bad input: invalid boxes, unknown and duplicate ids, mismatched spans. Every rejected call
// must throw the type errors.hpp names, mention the id at fault, and leave the world exactly
// as it was: same boxes, and the same pairs at the next detection as a twin world that never
// saw the bad call. Bad calls are made with changes pending since the last detection, so that
// a half-applied call would show.

#include <gtest/gtest.h>

#include <cstddef>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "reference/random_boxes.hpp"
#include "reference/reference_world.hpp"
#include "reference/world_types.hpp"
#include "smb/errors.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

/// An id that cannot be confused with a number in any other part of a message.
constexpr BoxId kBadId = 4242424242;

template <typename WorldType>
class WorldErrorTest : public ::testing::Test {
protected:
    using Real = typename WorldType::real_type;
    static constexpr int Dim = WorldType::dimension;
    using BoxT = Box<Real, Dim>;
    using BadCall = std::function<void(WorldType&)>;

    struct Corruption {
        std::string name;
        std::function<void(BoxT&)> apply;
    };

    void SetUp() override {
        for (BoxId id = 0; id < 150; ++id) apply_insert(id * 2, random_valid_box());
        world_.detect(scratch_);
        twin_.detect(scratch_);
    }

    BoxT random_valid_box() { return random_box<Real, Dim>(random_, 0, 12, 0.5, 2); }

    void apply_insert(BoxId id, const BoxT& box) {
        world_.insert(id, box);
        twin_.insert(id, box);
        reference_.insert(id, box);
    }

    /// Changes that both worlds receive and that no detection has folded in yet.
    void make_pending_changes() {
        const std::vector<BoxId> present = reference_.ids();
        for (int i = 0; i < 5; ++i) {
            const BoxId id = present[uniform_index(random_, present.size())];
            if (!reference_.contains(id)) continue;
            const BoxT box = perturbed(random_, reference_.box(id), 0.5, 0.2);
            world_.update(id, box);
            twin_.update(id, box);
            reference_.update(id, box);
        }
        const BoxId doomed = present[uniform_index(random_, present.size())];
        if (reference_.contains(doomed)) {
            world_.remove(doomed);
            twin_.remove(doomed);
            reference_.remove(doomed);
        }
        apply_insert(next_fresh_id_++, random_valid_box());
    }

    /// Every way to make a valid box invalid, on every axis.
    static std::vector<Corruption> corruptions() {
        constexpr Real nan = std::numeric_limits<Real>::quiet_NaN();
        constexpr Real inf = std::numeric_limits<Real>::infinity();
        std::vector<Corruption> out;
        for (int k = 0; k < Dim; ++k) {
            const std::string axis(1, "xyz"[k]);
            out.push_back({"NaN min " + axis, [k](BoxT& b) { b.min[k] = nan; }});
            out.push_back({"NaN max " + axis, [k](BoxT& b) { b.max[k] = nan; }});
            out.push_back({"+inf max " + axis, [k](BoxT& b) { b.max[k] = inf; }});
            out.push_back({"+inf min and max " + axis, [k](BoxT& b) { b.min[k] = b.max[k] = inf; }});
            out.push_back({"-inf min " + axis, [k](BoxT& b) { b.min[k] = -inf; }});
            out.push_back({"-inf min and max " + axis, [k](BoxT& b) { b.min[k] = b.max[k] = -inf; }});
            out.push_back({"min > max " + axis, [k](BoxT& b) { b.min[k] = b.max[k] + Real(1); }});
            out.push_back({"min just above max " + axis,
                           [k](BoxT& b) { b.min[k] = std::nextafter(b.max[k], std::numeric_limits<Real>::max()); }});
        }
        return out;
    }

    BoxT corrupted(const Corruption& corruption) {
        BoxT box = random_valid_box();
        corruption.apply(box);
        EXPECT_FALSE(is_valid(box)) << corruption.name;
        return box;
    }

    /// Makes pending changes, then `call`, which must throw Expected mentioning `mention`
    /// (when not empty), and checks that the world is as before.
    template <typename Expected>
    void expect_rejected(const std::string& what, const BadCall& call, const std::string& mention) {
        SCOPED_TRACE(what);
        make_pending_changes();
        const std::size_t size_before = world_.size();
        try {
            call(world_);
            ADD_FAILURE() << "no exception thrown";
        } catch (const Expected& error) {
            if (!mention.empty()) {
                EXPECT_NE(std::string(error.what()).find(mention), std::string::npos)
                    << "message \"" << error.what() << "\" does not mention " << mention;
            }
        } catch (const std::exception& error) {
            ADD_FAILURE() << "wrong exception type, message: " << error.what();
        }
        EXPECT_EQ(world_.size(), size_before);
        expect_unchanged();
    }

    void expect_unchanged() {
        EXPECT_TRUE(same_contents(world_, reference_));
        EXPECT_FALSE(world_.contains(kBadId));
        std::vector<Pair> pairs;
        std::vector<Pair> twin_pairs;
        world_.detect(pairs);
        twin_.detect(twin_pairs);
        const std::vector<Pair> expected = reference_.pairs();
        EXPECT_TRUE(same_pairs(pairs, expected, reference_.describer()));
        EXPECT_TRUE(same_pairs(twin_pairs, expected, reference_.describer()));
        sort_pairs(twin_pairs);
        EXPECT_TRUE(same_pairs(pairs, twin_pairs)) << "differs from the twin world";
    }

    /// Valid new boxes for a batch, with `bad` placed in the middle of it.
    void batch_with(const BoxT& bad, std::vector<BoxId>& ids, std::vector<BoxT>& boxes) {
        ids.clear();
        boxes.clear();
        for (int i = 0; i < 6; ++i) {
            ids.push_back(next_fresh_id_ + 1000 + static_cast<BoxId>(i));
            boxes.push_back(random_valid_box());
        }
        ids.insert(ids.begin() + 3, kBadId);
        boxes.insert(boxes.begin() + 3, bad);
    }

    /// Existing ids with moved boxes for a batch update, with `bad` under kBadId's place.
    void existing_batch(std::vector<BoxId>& ids, std::vector<BoxT>& boxes) {
        ids.clear();
        boxes.clear();
        const std::vector<BoxId> present = reference_.ids();
        for (std::size_t i = 0; i < 6 && i < present.size(); ++i) {
            ids.push_back(present[i * 7 % present.size()]);
            boxes.push_back(perturbed(random_, reference_.box(ids.back()), 1.0, 0.5));
        }
    }

    BoxId some_present_id() {
        const std::vector<BoxId> present = reference_.ids();
        return present[uniform_index(random_, present.size())];
    }

    Random random_{5150};
    WorldType world_{test_settings()};
    WorldType twin_{test_settings()};
    ReferenceWorld<Real, Dim> reference_;
    BoxId next_fresh_id_ = 100000;
    std::vector<Pair> scratch_;
};

TYPED_TEST_SUITE(WorldErrorTest, WorldTypes, WorldTypeNames);

TYPED_TEST(WorldErrorTest, InsertOfAnInvalidBox) {
    for (const auto& corruption : this->corruptions()) {
        const auto bad = this->corrupted(corruption);
        this->template expect_rejected<InvalidBoxError>(
            "insert, " + corruption.name, [&](TypeParam& w) { w.insert(kBadId, bad); }, std::to_string(kBadId));
    }
}

TYPED_TEST(WorldErrorTest, BatchInsertWithOneInvalidBox) {
    std::vector<BoxId> ids;
    std::vector<typename TestFixture::BoxT> boxes;
    for (const auto& corruption : this->corruptions()) {
        this->batch_with(this->corrupted(corruption), ids, boxes);
        this->template expect_rejected<InvalidBoxError>(
            "batch insert, " + corruption.name, [&](TypeParam& w) { w.insert(ids, boxes); }, std::to_string(kBadId));
        for (const BoxId id : ids) EXPECT_FALSE(this->world_.contains(id));
    }
}

TYPED_TEST(WorldErrorTest, UpdateToAnInvalidBox) {
    for (const auto& corruption : this->corruptions()) {
        const BoxId id = this->some_present_id();
        const auto bad = this->corrupted(corruption);
        this->template expect_rejected<InvalidBoxError>(
            "update, " + corruption.name, [&](TypeParam& w) { w.update(id, bad); }, std::to_string(id));
    }
}

TYPED_TEST(WorldErrorTest, BatchUpdateWithOneInvalidBox) {
    std::vector<BoxId> ids;
    std::vector<typename TestFixture::BoxT> boxes;
    for (const auto& corruption : this->corruptions()) {
        this->existing_batch(ids, boxes);
        ids.push_back(this->some_present_id());
        boxes.push_back(this->corrupted(corruption));
        ids.push_back(this->some_present_id());
        boxes.push_back(this->random_valid_box());
        const BoxId culprit = ids[ids.size() - 2];
        this->template expect_rejected<InvalidBoxError>(
            "batch update, " + corruption.name, [&](TypeParam& w) { w.update(ids, boxes); }, std::to_string(culprit));
    }
}

TYPED_TEST(WorldErrorTest, AssignWithOneInvalidBox) {
    for (const auto& corruption : this->corruptions()) {
        std::vector<typename TestFixture::BoxT> boxes;
        for (int i = 0; i < 400; ++i) boxes.push_back(this->random_valid_box());
        boxes[317] = this->corrupted(corruption);
        this->template expect_rejected<InvalidBoxError>(
            "assign, " + corruption.name, [&](TypeParam& w) { w.assign(boxes); }, "317");
    }
}

TYPED_TEST(WorldErrorTest, InsertOfAnIdAlreadyPresent) {
    const BoxId id = this->some_present_id();
    this->template expect_rejected<DuplicateIdError>(
        "insert of a present id", [&](TypeParam& w) { w.insert(id, this->random_valid_box()); }, std::to_string(id));
}

TYPED_TEST(WorldErrorTest, InsertOfAnIdInsertedSinceTheLastDetection) {
    this->apply_insert(kBadId + 1, this->random_valid_box());
    this->template expect_rejected<DuplicateIdError>(
        "insert of a pending id", [&](TypeParam& w) { w.insert(kBadId + 1, this->random_valid_box()); },
        std::to_string(kBadId + 1));
}

TYPED_TEST(WorldErrorTest, BatchInsertWithAnIdAlreadyPresent) {
    std::vector<BoxId> ids;
    std::vector<typename TestFixture::BoxT> boxes;
    this->batch_with(this->random_valid_box(), ids, boxes);
    const BoxId present = this->some_present_id();
    ids.back() = present;
    this->template expect_rejected<DuplicateIdError>(
        "batch insert against the world", [&](TypeParam& w) { w.insert(ids, boxes); }, std::to_string(present));
    for (std::size_t i = 0; i + 1 < ids.size(); ++i) EXPECT_FALSE(this->world_.contains(ids[i]));
}

// The message says which of the two an insert's duplicate is: named twice in the batch, or
// already in the world.
TYPED_TEST(WorldErrorTest, BatchInsertNamingAnIdTwiceSaysItIsRepeatedInTheBatch) {
    std::vector<BoxId> ids;
    std::vector<typename TestFixture::BoxT> boxes;
    this->batch_with(this->random_valid_box(), ids, boxes);
    ids.push_back(kBadId);
    boxes.push_back(this->random_valid_box());
    this->template expect_rejected<DuplicateIdError>(
        "batch insert with an id twice", [&](TypeParam& w) { w.insert(ids, boxes); },
        std::to_string(kBadId) + " is repeated in the batch");
    const BoxId present = this->some_present_id();
    ids.back() = present;
    this->template expect_rejected<DuplicateIdError>(
        "batch insert against the world", [&](TypeParam& w) { w.insert(ids, boxes); },
        std::to_string(present) + " is already in the world");
}

TYPED_TEST(WorldErrorTest, RemoveOfAnUnknownId) {
    this->template expect_rejected<UnknownIdError>(
        "remove", [](TypeParam& w) { w.remove(kBadId); }, std::to_string(kBadId));
}

TYPED_TEST(WorldErrorTest, RemoveOfAnIdRemovedSinceTheLastDetection) {
    const BoxId id = this->some_present_id();
    this->world_.remove(id);
    this->twin_.remove(id);
    this->reference_.remove(id);
    this->template expect_rejected<UnknownIdError>(
        "second remove", [&](TypeParam& w) { w.remove(id); }, std::to_string(id));
}

TYPED_TEST(WorldErrorTest, BatchRemoveWithOneUnknownId) {
    std::vector<BoxId> ids = this->reference_.ids();
    ids.resize(10);
    ids.push_back(kBadId);
    this->template expect_rejected<UnknownIdError>(
        "batch remove, unknown id last", [&](TypeParam& w) { w.remove(ids); }, std::to_string(kBadId));
    for (std::size_t i = 0; i + 1 < ids.size(); ++i) EXPECT_TRUE(this->world_.contains(ids[i]));
}

TYPED_TEST(WorldErrorTest, BatchRemoveNamingAnIdTwice) {
    std::vector<BoxId> ids = this->reference_.ids();
    ids.resize(10);
    const BoxId twice = ids[4];
    ids.push_back(twice);
    this->template expect_rejected<DuplicateIdError>(
        "batch remove with an id twice", [&](TypeParam& w) { w.remove(ids); }, std::to_string(twice));
}

TYPED_TEST(WorldErrorTest, UpdateOfAnUnknownId) {
    this->template expect_rejected<UnknownIdError>(
        "update", [&](TypeParam& w) { w.update(kBadId, this->random_valid_box()); }, std::to_string(kBadId));
}

TYPED_TEST(WorldErrorTest, UpdateOfAnIdRemovedSinceTheLastDetection) {
    const BoxId id = this->some_present_id();
    this->world_.remove(id);
    this->twin_.remove(id);
    this->reference_.remove(id);
    this->template expect_rejected<UnknownIdError>(
        "update after remove", [&](TypeParam& w) { w.update(id, this->random_valid_box()); }, std::to_string(id));
}

TYPED_TEST(WorldErrorTest, BatchUpdateWithOneUnknownId) {
    std::vector<BoxId> ids;
    std::vector<typename TestFixture::BoxT> boxes;
    this->existing_batch(ids, boxes);
    ids.push_back(kBadId);
    boxes.push_back(this->random_valid_box());
    this->template expect_rejected<UnknownIdError>(
        "batch update, unknown id last", [&](TypeParam& w) { w.update(ids, boxes); }, std::to_string(kBadId));
}

TYPED_TEST(WorldErrorTest, MismatchedSpanLengths) {
    std::vector<BoxId> ids;
    std::vector<typename TestFixture::BoxT> boxes;
    this->batch_with(this->random_valid_box(), ids, boxes);
    ids.pop_back();
    this->template expect_rejected<ArgumentError>(
        "insert with fewer ids", [&](TypeParam& w) { w.insert(ids, boxes); }, "");
    this->existing_batch(ids, boxes);
    boxes.pop_back();
    this->template expect_rejected<ArgumentError>(
        "update with fewer boxes", [&](TypeParam& w) { w.update(ids, boxes); }, "");
    this->template expect_rejected<ArgumentError>(
        "insert of ids without boxes",
        [&](TypeParam& w) { w.insert(ids, std::span<const typename TestFixture::BoxT>()); }, "");
}

TYPED_TEST(WorldErrorTest, BoxOfAnUnknownId) {
    EXPECT_THROW((void)this->world_.box(kBadId), UnknownIdError);
    EXPECT_FALSE(this->world_.contains(kBadId));
}

TYPED_TEST(WorldErrorTest, DetectIntoAnEmptySink) {
    this->template expect_rejected<ArgumentError>(
        "empty sink", [](TypeParam& w) { w.detect(PairSink{}); }, "");
}

TYPED_TEST(WorldErrorTest, EmptyBatchesAreNotErrors) {
    this->make_pending_changes();
    this->world_.insert(std::span<const BoxId>(), std::span<const typename TestFixture::BoxT>());
    this->world_.update(std::span<const BoxId>(), std::span<const typename TestFixture::BoxT>());
    this->world_.remove(std::span<const BoxId>());
    this->expect_unchanged();
}

TYPED_TEST(WorldErrorTest, ManyRejectedCallsInARowThenNormalUse) {
    const auto bad = this->corrupted(this->corruptions().front());
    this->make_pending_changes();
    for (int i = 0; i < 20; ++i) {
        EXPECT_THROW(this->world_.insert(kBadId, bad), InvalidBoxError);
        EXPECT_THROW(this->world_.remove(kBadId), UnknownIdError);
        EXPECT_THROW(this->world_.update(kBadId, this->random_valid_box()), UnknownIdError);
    }
    this->expect_unchanged();
    const auto good = this->random_valid_box();
    this->apply_insert(kBadId - 1, good);
    this->expect_unchanged();
}

TEST(ErrorHierarchy, EverySmbErrorIsAnInvalidArgument) {
    World3d world;
    EXPECT_THROW(world.remove(1), Error);
    EXPECT_THROW(world.remove(1), std::invalid_argument);
    Box3d inverted;
    inverted.min = {1, 0, 0};
    inverted.max = {0, 1, 1};
    EXPECT_THROW(world.insert(1, inverted), Error);
    world.insert(1, Box3d{});
    EXPECT_THROW(world.insert(1, Box3d{}), Error);
}

TEST(SettingsErrors, ZeroCellPopulationOrChunkSizeIsRejected) {
    WorldSettings no_population;
    no_population.target_cell_population = 0;
    EXPECT_THROW(World2d{no_population}, ArgumentError);
    WorldSettings no_chunk;
    no_chunk.pair_chunk_size = 0;
    EXPECT_THROW(World3f{no_chunk}, ArgumentError);
}

TEST(SettingsErrors, TooManyThreadsOrAnUnknownPipelineIsRejected) {
    WorldSettings crowd;
    crowd.threads = 5000;
    EXPECT_THROW(World3d{crowd}, ArgumentError);
    crowd.threads = 1024;
    EXPECT_NO_THROW(World3d{crowd});
    WorldSettings unknown;
    unknown.pipeline = static_cast<Pipeline>(7);
    EXPECT_THROW(World2f{unknown}, ArgumentError);
}

}  // namespace
}  // namespace smb::test
