// SPDX-License-Identifier: MIT
// The check every Detector input passes (src/core/scene_bounds.hpp): the bounds of the boxes and
// the first invalid box, whichever lane of the four-lane scan of float boxes holds the bad
// coordinate, whichever of the scan's two sets of lanes holds the box, and however many boxes
// there are (an odd count leaves one box to the end), against a plain loop.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "core/scene_bounds.hpp"
#include "reference/detector_shapes.hpp"
#include "smb/box.hpp"
#include "smb/errors.hpp"

namespace smb::detail {
namespace {

template <class T>
class SceneBoundsTest : public ::testing::Test {};
TYPED_TEST_SUITE(SceneBoundsTest, test::Shapes, test::ShapeNames);

template <class Real, int Dim>
std::vector<Box<Real, Dim>> random_boxes(std::size_t n, std::mt19937& random) {
    std::uniform_real_distribution<Real> place(-50, 50);
    std::uniform_real_distribution<Real> side(0, 3);
    std::vector<Box<Real, Dim>> boxes(n);
    for (auto& box : boxes) {
        for (int k = 0; k < Dim; ++k) {
            box.min[k] = place(random);
            box.max[k] = box.min[k] + side(random);
        }
    }
    return boxes;
}

TYPED_TEST(SceneBoundsTest, BoundsAreThoseOfAPlainLoop) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    std::mt19937 random(7);
    for (const std::size_t n : {1U, 2U, 3U, 4U, 5U, 16U, 17U, 1001U}) {
        const auto boxes = random_boxes<Real, Dim>(n, random);
        const SceneBounds<Real, Dim> bounds = checked_bounds(std::span<const Box<Real, Dim>>(boxes));
        for (int k = 0; k < Dim; ++k) {
            Real lo = boxes[0].min[k];
            Real hi = boxes[0].max[k];
            for (const auto& box : boxes) {
                lo = std::min(lo, box.min[k]);
                hi = std::max(hi, box.max[k]);
            }
            EXPECT_EQ(bounds.lo[k], lo) << "n " << n << " axis " << k;
            EXPECT_EQ(bounds.hi[k], hi) << "n " << n << " axis " << k;
        }
    }
}

TYPED_TEST(SceneBoundsTest, EveryBadCoordinateOfEveryBoxIsNamed) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    const Real inf = std::numeric_limits<Real>::infinity();
    std::mt19937 random(11);
    for (const std::size_t n : {1U, 2U, 3U, 6U, 7U}) {
        const auto boxes = random_boxes<Real, Dim>(n, random);
        for (std::size_t bad_box = 0; bad_box < n; ++bad_box) {
            for (int axis = 0; axis < Dim; ++axis) {
                for (int kind = 0; kind < 7; ++kind) {
                    auto broken = boxes;
                    Box<Real, Dim>& box = broken[bad_box];
                    switch (kind) {
                        case 0:
                            box.min[axis] = nan;
                            break;
                        case 1:
                            box.max[axis] = nan;
                            break;
                        case 2:
                            box.min[axis] = -inf;
                            break;
                        case 3:
                            box.max[axis] = inf;
                            break;
                        case 4:
                            box.min[axis] = box.max[axis] = inf;
                            break;
                        case 5:
                            box.min[axis] = box.max[axis] = -inf;
                            break;
                        default:
                            box.min[axis] = box.max[axis] + 1;
                            break;
                    }
                    try {
                        (void)checked_bounds(std::span<const Box<Real, Dim>>(broken));
                        ADD_FAILURE() << "no error: n " << n << " box " << bad_box << " axis " << axis << " kind "
                                      << kind;
                    } catch (const InvalidBoxError& error) {
                        EXPECT_NE(std::string(error.what()).find("box " + std::to_string(bad_box)), std::string::npos)
                            << error.what();
                    }
                }
            }
        }
    }
}

}  // namespace
}  // namespace smb::detail
