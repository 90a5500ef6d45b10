// SPDX-License-Identifier: MIT
// Bad input on one rank makes every rank throw the same error, and none hangs (a hang fails the
// test by CTest's timeout); the detector is usable again afterwards.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "mpi/mpi_scene.hpp"
#include "smb/mpi/distributed_detector.hpp"

namespace smb::mpi::test {
namespace {

/// Every rank's message, checked equal to rank 0's.
void expect_same_message_everywhere(const std::string& message) {
    int length = static_cast<int>(message.size());
    MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::string first(static_cast<std::size_t>(length), '\0');
    if (rank_of() == 0) first = message;
    MPI_Bcast(first.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
    EXPECT_EQ(message, first);
}

/// Ten good boxes per rank, ids rank * 10 + i, a row of touching unit boxes.
void good_share(std::vector<BoxId>& ids, std::vector<Box3d>& boxes) {
    ids.clear();
    boxes.clear();
    for (int i = 0; i < 10; ++i) {
        const double x = rank_of() * 10 + i;
        ids.push_back(static_cast<BoxId>(rank_of() * 10 + i));
        boxes.push_back(Box3d{{x, 0, 0}, {x + 1, 1, 1}});
    }
}

/// Calls detect on every rank; expects every rank to throw ErrorT with one message, and then a
/// good step to give the row's pairs.
template <class ErrorT>
void expect_thrown_everywhere(DistributedDetector3d& detector, const std::vector<BoxId>& ids,
                              const std::vector<Box3d>& boxes, const std::string& naming) {
    std::vector<Pair> pairs{{1, 2}};
    std::string message;
    bool thrown = false;
    try {
        detector.detect(ids, boxes, pairs);
    } catch (const ErrorT& error) {
        thrown = true;
        message = error.what();
    }
    EXPECT_TRUE(thrown);
    EXPECT_NE(message.find(naming), std::string::npos) << message;
    EXPECT_EQ(pairs, (std::vector<Pair>{{1, 2}}));  // as it was
    expect_same_message_everywhere(message);

    std::vector<BoxId> good_ids;
    std::vector<Box3d> good_boxes;
    good_share(good_ids, good_boxes);
    detector.detect(good_ids, good_boxes, pairs);
    const std::vector<RankedPair> all = gather_pairs(pairs);
    EXPECT_EQ(all.size(), static_cast<std::size_t>(10 * ranks_of() - 1));  // neighbours along the row
}

class DistributedErrors : public ::testing::Test {
protected:
    void SetUp() override {
        good_share(ids, boxes);
        detector.detect(ids, boxes, pairs);  // a first good step: the errors come on later ones
    }
    DistributedDetector3d detector{MPI_COMM_WORLD};
    std::vector<BoxId> ids;
    std::vector<Box3d> boxes;
    std::vector<Pair> pairs;
    int last = ranks_of() - 1;
};

TEST_F(DistributedErrors, NaNBoxOnTheLastRank) {
    if (rank_of() == last) boxes[3].min[1] = std::numeric_limits<double>::quiet_NaN();
    expect_thrown_everywhere<InvalidBoxError>(detector, ids, boxes, "box " + std::to_string(last * 10 + 3));
}

TEST_F(DistributedErrors, MinAboveMaxOnRankZeroAndInfinityOnTheLast) {
    if (rank_of() == 0) boxes[5].min[0] = boxes[5].max[0] + 1;
    if (rank_of() == last) boxes[7].max[2] = std::numeric_limits<double>::infinity();
    expect_thrown_everywhere<InvalidBoxError>(detector, ids, boxes, "box 5 ");
}

TEST_F(DistributedErrors, DuplicateIdAcrossRanks) {
    // The last rank passes rank 0's id 4 as well (on one rank: twice on the same rank).
    if (rank_of() == last) ids[8] = 4;
    if (ranks_of() == 1) ids[8] = 4;
    expect_thrown_everywhere<DuplicateIdError>(detector, ids, boxes, "id 4 ");
}

TEST_F(DistributedErrors, DuplicateLargestIdOnTheFirstStep) {
    DistributedDetector3d fresh(MPI_COMM_WORLD);
    if (rank_of() == 0) ids[0] = std::numeric_limits<BoxId>::max();
    if (rank_of() == last) ids[9] = std::numeric_limits<BoxId>::max();
    expect_thrown_everywhere<DuplicateIdError>(fresh, ids, boxes, std::to_string(std::numeric_limits<BoxId>::max()));
}

TEST_F(DistributedErrors, SameNewIdInsertedByTwoRanksAtOnce) {
    // Only the inserted ids travel: the repeat is found among them (on one rank: twice there).
    ids[2] = 1000;
    if (rank_of() == last) ids[6] = 1000;
    if (ranks_of() == 1) ids[6] = 1000;
    expect_thrown_everywhere<DuplicateIdError>(detector, ids, boxes, "id 1000 ");
}

TEST_F(DistributedErrors, AnIdPassedFromOneRankToAnotherIsNoRepeat) {
    // The last rank's last box goes to rank 0: removed by one, inserted by the other at once.
    const BoxId moving = static_cast<BoxId>(last * 10 + 9);
    const Box3d box = Box3d{{static_cast<double>(moving), 0, 0}, {static_cast<double>(moving) + 1, 1, 1}};
    if (rank_of() == last) {
        ids.pop_back();
        boxes.pop_back();
    }
    if (rank_of() == 0) {
        ids.push_back(moving);
        boxes.push_back(box);
    }
    for (int step = 0; step < 2; ++step) {
        detector.detect(ids, boxes, pairs);
        EXPECT_EQ(gather_pairs(pairs).size(), static_cast<std::size_t>(10 * ranks_of() - 1));
    }
    // And the id it left behind is free: the last rank may not take it back while rank 0 has it.
    if (ranks_of() > 1 && rank_of() == last) {
        ids.push_back(moving);
        boxes.push_back(box);
    }
    if (ranks_of() == 1) ids.push_back(moving), boxes.push_back(box);
    expect_thrown_everywhere<DuplicateIdError>(detector, ids, boxes, "id " + std::to_string(moving) + " ");
}

TEST_F(DistributedErrors, LengthsDifferOnOneRank) {
    if (rank_of() == last) ids.pop_back();
    expect_thrown_everywhere<ArgumentError>(detector, ids, boxes, "differ in length on 1 rank");
}

TEST(DistributedSettingsCheck, ThresholdBelowOneIsRefused) {
    DistributedSettings settings;
    settings.rebalance_threshold = 0.1;
    try {
        DistributedDetector3d detector(MPI_COMM_WORLD, settings);
        ADD_FAILURE() << "a threshold of 0.1 was taken";
    } catch (const ArgumentError& error) {
        // The number as the caller wrote it, not std::to_string's 0.100000.
        EXPECT_NE(std::string(error.what()).find("at least 1, not 0.1"), std::string::npos) << error.what();
        EXPECT_EQ(std::string(error.what()).find("0.100000"), std::string::npos) << error.what();
    }
}

}  // namespace
}  // namespace smb::mpi::test
