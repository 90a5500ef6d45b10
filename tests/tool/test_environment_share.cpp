// SPDX-License-Identifier: MIT
// One rank's share of the paper's environment: the shares of every part together are the serial
// environment's rows, bit for bit, at every step, whatever the number of parts; each share holds
// only its own rows.

#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include "smb/workload/dynamic_environment.hpp"
#include "smb/workload/environment_share.hpp"

namespace smb::workload {
namespace {

template <int Dim>
void expect_shares_equal_serial(const EnvironmentParams& params, int parts, int steps) {
    DynamicEnvironment<Dim> serial(params);
    std::vector<EnvironmentShare<Dim>> shares;
    for (int part = 0; part < parts; ++part) shares.emplace_back(params, part, parts);
    for (int step = 0; step <= steps; ++step) {
        if (step > 0) {
            serial.step();
            for (auto& share : shares) share.step();
        }
        // Row i of the serial scene is row i / parts of share ids[i] mod parts, in id order.
        std::vector<std::size_t> next_row(static_cast<std::size_t>(parts), 0);
        for (std::size_t i = 0; i < serial.size(); ++i) {
            const BoxId id = serial.ids()[i];
            const auto part = static_cast<std::size_t>(id % static_cast<BoxId>(parts));
            const auto& share = shares[part];
            const std::size_t row = next_row[part]++;
            ASSERT_LT(row, share.ids().size()) << "step " << step << " part " << part;
            ASSERT_EQ(share.ids()[row], id) << "step " << step << " part " << part;
            ASSERT_EQ(std::memcmp(&share.boxes()[row], &serial.boxes()[i], sizeof(Box<double, Dim>)), 0)
                << "step " << step << " id " << id;
        }
        for (std::size_t part = 0; part < shares.size(); ++part) {
            EXPECT_EQ(next_row[part], shares[part].ids().size()) << "step " << step << " part " << part;
            EXPECT_EQ(shares[part].global_size(), serial.size());
        }
        EXPECT_EQ(shares.front().cube_side(), serial.cube_side());
    }
}

EnvironmentParams params_with(std::size_t box_count, double update_factor, std::uint64_t seed) {
    EnvironmentParams params;
    params.box_count = box_count;
    params.update_factor = update_factor;
    params.seed = seed;
    return params;
}

TEST(EnvironmentShare, SharesAreTheSerialRows2d) {
    for (int parts : {1, 2, 3, 7}) expect_shares_equal_serial<2>(params_with(600, 0.05, 11), parts, 10);
}

TEST(EnvironmentShare, SharesAreTheSerialRows3d) {
    for (int parts : {1, 2, 4, 5}) expect_shares_equal_serial<3>(params_with(500, 0.05, 12), parts, 10);
}

TEST(EnvironmentShare, MostBoxesDeletedInOneStep) {
    // Λ above 1/2: a step may delete more than half, when the spared boxes are drawn instead.
    for (std::uint64_t seed = 1; seed <= 4; ++seed) expect_shares_equal_serial<3>(params_with(300, 0.9, seed), 3, 6);
}

TEST(EnvironmentShare, PaperUpdateFactor) { expect_shares_equal_serial<3>(params_with(4000, 1e-3, 5), 4, 4); }

TEST(EnvironmentShare, MorePartsThanBoxes) { expect_shares_equal_serial<2>(params_with(3, 0.3, 2), 8, 5); }

TEST(EnvironmentShare, BadPartOrBadParametersThrow) {
    EXPECT_THROW(EnvironmentShare<2>(params_with(10, 0.1, 1), 2, 2), std::invalid_argument);
    EXPECT_THROW(EnvironmentShare<2>(params_with(10, 0.1, 1), -1, 2), std::invalid_argument);
    EXPECT_THROW(EnvironmentShare<2>(params_with(10, 0.1, 1), 0, 0), std::invalid_argument);
    EXPECT_THROW(EnvironmentShare<3>(params_with(10, 1.5, 1), 0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace smb::workload
