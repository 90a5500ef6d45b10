// SPDX-License-Identifier: MIT
// The world against brute force on eight families of scenes that stress different parts of the
// cut (ties on an integer lattice, sizes over six orders of magnitude, clusters, coordinates
// near ±1e9, tiny offsets at 1e9, long sticks, very dense piles), with heavy churn: boxes
// redrawn from other families, moved, removed and inserted, an occasional clear(), and cell
// populations from 1 to 100. Seeded; a failure names its seed.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "reference/brute_force.hpp"
#include "reference/world_types.hpp"
#include "smb/smb.hpp"

namespace smb {
namespace {

class Draw {
public:
    explicit Draw(std::uint64_t seed) : rng_(seed) {}
    double unit() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }
    std::uint64_t bits() { return rng_(); }

    template <std::floating_point Real, int Dim>
    Box<Real, Dim> box(int family, double scale) {
        Box<Real, Dim> b;
        for (int k = 0; k < Dim; ++k) {
            double centre = 0;
            double side = 0;
            switch (family) {
                case 0:
                    centre = unit() * scale;
                    side = unit() * 2;
                    break;
                case 1:
                    centre = std::floor(unit() * 6);
                    side = std::floor(unit() * 3);
                    break;
                case 2:
                    centre = unit() * scale;
                    side = std::pow(10.0, -3 + 6 * unit());
                    break;
                case 3:
                    centre = std::floor(unit() * 4) * scale / 4 + unit() * 2;
                    side = unit() * 0.5;
                    break;
                case 4:
                    centre = (unit() * 2 - 1) * 1e9;
                    side = unit() < 0.5 ? 0 : unit() * 1e8;
                    break;
                case 5:
                    centre = 1e9 + std::floor(unit() * 20) * 0.25;
                    side = std::floor(unit() * 3) * 0.25;
                    break;
                case 6:
                    centre = unit() * scale;
                    side = (k == 0 ? scale : 0.3) * unit();
                    break;
                default:
                    centre = unit() * 3;
                    side = unit() * 3;
                    break;
            }
            b.min[k] = static_cast<Real>(centre);
            b.max[k] = std::max(b.min[k], static_cast<Real>(centre + side));
        }
        return b;
    }

private:
    std::mt19937_64 rng_;
};

template <class WorldType>
class MixedDistributionsTest : public ::testing::Test {};
TYPED_TEST_SUITE(MixedDistributionsTest, test::WorldTypes);

TYPED_TEST(MixedDistributionsTest, MatchesBruteForceUnderChurn) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    constexpr std::size_t populations[] = {1, 2, 3, 5, 24, 100};
    for (std::uint64_t seed = 1; seed <= test::scaled(48); ++seed) {
        Draw draw(seed * 977 + Dim);
        const int family = static_cast<int>(seed % 8);
        WorldSettings settings = ::smb::test::test_settings();
        settings.target_cell_population = populations[seed % 6];
        TypeParam world(settings);
        std::vector<BoxId> ids;
        std::vector<Box<Real, Dim>> boxes;
        BoxId next = 0;
        const std::size_t start = 50 + draw.bits() % 250;
        const double scale = 5 + draw.unit() * 40;
        for (std::size_t i = 0; i < start; ++i) {
            ids.push_back(next);
            boxes.push_back(draw.box<Real, Dim>(family, scale));
            world.insert(next++, boxes.back());
        }
        for (int step = 0; step < 12; ++step) {
            const double churn = draw.unit();
            for (std::size_t i = 0; i < ids.size(); ++i) {
                if (draw.unit() < 0.05 + 0.3 * churn) {
                    const int other = draw.unit() < 0.2 ? static_cast<int>(draw.bits() % 8) : family;
                    boxes[i] = draw.box<Real, Dim>(other, scale);
                    world.update(ids[i], boxes[i]);
                } else if (draw.unit() < 0.5) {
                    for (int k = 0; k < Dim; ++k) {
                        const auto shift = static_cast<Real>((draw.unit() - 0.5) * 0.1);
                        boxes[i].min[k] += shift;
                        boxes[i].max[k] += shift;
                    }
                    world.update(ids[i], boxes[i]);
                }
            }
            const auto removals = static_cast<std::size_t>(draw.unit() * static_cast<double>(ids.size()) * 0.2 * churn);
            for (std::size_t r = 0; r < removals && !ids.empty(); ++r) {
                const std::size_t i = draw.bits() % ids.size();
                world.remove(ids[i]);
                ids[i] = ids.back();
                ids.pop_back();
                boxes[i] = boxes.back();
                boxes.pop_back();
            }
            const auto insertions = static_cast<std::size_t>(draw.unit() * static_cast<double>(start) * 0.2 * churn);
            for (std::size_t r = 0; r < insertions; ++r) {
                ids.push_back(next);
                boxes.push_back(draw.box<Real, Dim>(family, scale));
                world.insert(next++, boxes.back());
            }
            if (draw.unit() < 0.03) {
                world.clear();
                ids.clear();
                boxes.clear();
            }
            std::vector<Pair> got;
            world.detect(got);
            sort_pairs(got);
            const auto expected = test::brute_force_pairs<Real, Dim>(ids, boxes);
            ASSERT_EQ(got, expected) << "seed " << seed << ", family " << family << ", population "
                                     << settings.target_cell_population << ", step " << step;
        }
    }
}

}  // namespace
}  // namespace smb
