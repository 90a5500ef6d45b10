// SPDX-License-Identifier: MIT
// The cell check (src/cuts/cell_pairs.hpp) both ways: testing every pair and sweeping on x
// report the same pairs and the same home boxes as a direct test under the lower-corner rule, at
// every size around the limit between them, in float and double, with the boxes registered in
// any order; and the keys of its sort on x.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <span>
#include <utility>
#include <vector>

#include "cuts/cell_pairs.hpp"
#include "smb/pair.hpp"

namespace smb::detail {
namespace {

template <class Real, int Dim>
struct Cell {
    std::vector<Box<Real, Dim>> boxes;
    std::vector<std::uint32_t> entries;  // positions registered in the cell, in any order
    std::vector<BoxId> ids;
    CellFloor<Real, Dim> floor{};
};

using PairSet = std::set<std::pair<std::uint32_t, std::uint32_t>>;

std::pair<std::uint32_t, std::uint32_t> ordered(std::uint32_t a, std::uint32_t b) {
    return a < b ? std::pair{a, b} : std::pair{b, a};
}

/// The pairs the cell must report: overlapping, with the lower corner of their intersection at or
/// above the floor on every axis.
template <class Real, int Dim>
PairSet expected_pairs(const Cell<Real, Dim>& cell) {
    PairSet pairs;
    for (std::size_t i = 0; i < cell.entries.size(); ++i) {
        for (std::size_t j = i + 1; j < cell.entries.size(); ++j) {
            const auto& a = cell.boxes[cell.entries[i]];
            const auto& b = cell.boxes[cell.entries[j]];
            bool here = overlaps(a, b);
            for (int k = 0; k < Dim; ++k) here = here && std::max(a.min[k], b.min[k]) >= cell.floor[k];
            if (here) pairs.insert(ordered(cell.entries[i], cell.entries[j]));
        }
    }
    return pairs;
}

template <class Real, int Dim>
BulkVector<std::uint32_t> expected_home(const Cell<Real, Dim>& cell) {
    BulkVector<std::uint32_t> home;
    for (const std::uint32_t position : cell.entries) {
        bool inside = true;
        for (int k = 0; k < Dim; ++k) inside = inside && cell.boxes[position].min[k] >= cell.floor[k];
        if (inside) home.push_back(position);
    }
    return home;
}

/// m boxes on a small lattice of coordinates (so that touching, identical and zero-size boxes
/// are common), some far out or spanning the whole cell, registered in a shuffled order.
template <class Real, int Dim>
Cell<Real, Dim> random_cell(std::mt19937_64& random, std::size_t m) {
    Cell<Real, Dim> cell;
    std::uniform_int_distribution<int> lattice(0, 24);
    for (std::size_t i = 0; i < m; ++i) {
        Box<Real, Dim> box;
        for (int k = 0; k < Dim; ++k) {
            Real lo = static_cast<Real>(lattice(random)) * Real{0.25};
            Real hi = lo + static_cast<Real>(lattice(random) % 6) * Real{0.25};
            if (random() % 23 == 0) lo = -std::numeric_limits<Real>::max();
            if (random() % 29 == 0) hi = std::numeric_limits<Real>::max();
            if (random() % 31 == 0) lo = hi;
            box.min[k] = lo;
            box.max[k] = hi;
        }
        cell.boxes.push_back(box);
        cell.ids.push_back(static_cast<BoxId>(1000 + (i * 7919) % (m + 1)));
        cell.entries.push_back(static_cast<std::uint32_t>(i));
    }
    std::shuffle(cell.entries.begin(), cell.entries.end(), random);
    for (int k = 0; k < Dim; ++k) {
        cell.floor[k] = random() % 3 == 0 ? -std::numeric_limits<Real>::infinity()
                                          : static_cast<Real>(lattice(random)) * Real{0.125};
    }
    return cell;
}

template <class Real, int Dim>
struct Checked {
    PairSet pairs;
    std::size_t reports = 0;
    BulkVector<std::uint32_t> home;
};

template <class Real, int Dim, class Run>
Checked<Real, Dim> run_check(Run&& run) {
    Checked<Real, Dim> out;
    auto report = [&](std::uint32_t a, std::uint32_t b) {
        ++out.reports;
        out.pairs.insert(ordered(a, b));
    };
    run(report, out.home);
    return out;
}

template <class T>
class CellPairsTest : public ::testing::Test {};

template <class Real, int D>
struct Kind {
    using real_type = Real;
    static constexpr int dimension = D;
};
using Kinds = ::testing::Types<Kind<float, 2>, Kind<float, 3>, Kind<double, 2>, Kind<double, 3>>;
TYPED_TEST_SUITE(CellPairsTest, Kinds);

TYPED_TEST(CellPairsTest, AllPairsAndSweepReportTheSamePairsOnce) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    constexpr std::size_t limit = CellPairs<Real, Dim>::kAllPairsLimit;
    std::mt19937_64 random(17 + Dim);
    CellPairs<Real, Dim> cell_pairs;  // one object throughout: its buffers are reused, as in the pipeline
    // 1200 boxes pass tens of thousands of pairs: the sweep hands its hit list on many times.
    for (const std::size_t m :
         {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{7}, std::size_t{8}, std::size_t{9},
          std::size_t{31}, limit - 1, limit, limit + 1, std::size_t{300}, std::size_t{1200}}) {
        for (int trial = 0; trial < 6; ++trial) {
            SCOPED_TRACE(::testing::Message() << "m " << m << ", trial " << trial);
            const Cell<Real, Dim> cell = random_cell<Real, Dim>(random, m);
            const std::span<const std::uint32_t> entries(cell.entries);
            const std::span<const Box<Real, Dim>> boxes(cell.boxes);
            const std::span<const BoxId> ids(cell.ids);
            const PairSet expected = expected_pairs(cell);
            BulkVector<std::uint32_t> home = expected_home(cell);

            const auto all_pairs = run_check<Real, Dim>(
                [&](auto& report, auto& out) { cell_pairs.check_all_pairs(entries, boxes, cell.floor, report, out); });
            EXPECT_EQ(all_pairs.pairs, expected);
            EXPECT_EQ(all_pairs.reports, expected.size()) << "a pair reported twice";
            EXPECT_EQ(all_pairs.home, home) << "home boxes in the order they were registered";

            const auto swept = run_check<Real, Dim>([&](auto& report, auto& out) {
                cell_pairs.check_by_sweep(entries, boxes, ids, cell.floor, report, out);
            });
            EXPECT_EQ(swept.pairs, expected);
            EXPECT_EQ(swept.reports, expected.size()) << "a pair reported twice";
            EXPECT_TRUE(std::is_sorted(swept.home.begin(), swept.home.end(), [&](std::uint32_t a, std::uint32_t b) {
                return cell.boxes[a].min[0] < cell.boxes[b].min[0];
            })) << "home boxes in x order";
            // What a column's queries lean on (Cells::widest): every box once, in x order, none
            // wider along x than the bound.
            std::vector<std::uint32_t> swept_positions(cell_pairs.swept_positions().begin(),
                                                       cell_pairs.swept_positions().end());
            EXPECT_TRUE(std::is_sorted(
                swept_positions.begin(), swept_positions.end(),
                [&](std::uint32_t a, std::uint32_t b) { return cell.boxes[a].min[0] < cell.boxes[b].min[0]; }));
            for (const std::uint32_t position : swept_positions) {
                const Box<Real, Dim>& box = cell.boxes[position];
                EXPECT_GE(cell_pairs.widest_x(), box.max[0] - box.min[0]);
                EXPECT_GE(box.min[0] + cell_pairs.widest_x(), box.max[0]);
            }
            std::sort(swept_positions.begin(), swept_positions.end());
            std::vector<std::uint32_t> sorted_entries(cell.entries);
            std::sort(sorted_entries.begin(), sorted_entries.end());
            EXPECT_EQ(swept_positions, sorted_entries);
            BulkVector<std::uint32_t> swept_home = swept.home;
            std::sort(swept_home.begin(), swept_home.end());
            std::sort(home.begin(), home.end());
            EXPECT_EQ(swept_home, home);

            const auto checked = run_check<Real, Dim>(
                [&](auto& report, auto& out) { cell_pairs.check(entries, boxes, ids, cell.floor, report, out); });
            EXPECT_EQ(checked.pairs, expected);
            EXPECT_EQ(checked.home, m <= limit ? all_pairs.home : swept.home) << "check() takes the way its size asks";
        }
    }
}

/// A column of m boxes spread over `x_span` along x, each at most one wide on x and crowded on
/// the other axes: its rows reach about m / x_span boxes along x.
template <class Real, int Dim>
Cell<Real, Dim> spread_cell(std::mt19937_64& random, std::size_t m, double x_span) {
    Cell<Real, Dim> cell;
    std::uniform_real_distribution<double> along(0.0, x_span);
    std::uniform_int_distribution<int> lattice(0, 8);
    for (std::size_t i = 0; i < m; ++i) {
        Box<Real, Dim> box;
        box.min[0] = static_cast<Real>(along(random));
        box.max[0] = box.min[0] + static_cast<Real>(lattice(random)) / Real{8};
        for (int k = 1; k < Dim; ++k) {
            box.min[k] = static_cast<Real>(lattice(random)) * Real{0.25};
            box.max[k] = box.min[k] + static_cast<Real>(lattice(random) % 5) * Real{0.25};
        }
        cell.boxes.push_back(box);
        cell.ids.push_back(static_cast<BoxId>(i));
        cell.entries.push_back(static_cast<std::uint32_t>(i));
    }
    std::shuffle(cell.entries.begin(), cell.entries.end(), random);
    cell.floor[0] = -std::numeric_limits<Real>::infinity();
    for (int k = 1; k < Dim; ++k)
        cell.floor[k] = random() % 2 == 0 ? -std::numeric_limits<Real>::infinity() : Real{0.5};
    return cell;
}

TEST(CellPairs, SweepReportsEveryPairWhetherRowsAreShortOrLong) {
    std::mt19937_64 random(99);
    CellPairs<float, 3> cell_pairs;
    // Rows that reach about 1, 5, 20 and 300 boxes: one group of lanes a turn, then two.
    for (const double x_span : {1000.0, 200.0, 50.0, 4.0}) {
        for (int trial = 0; trial < 4; ++trial) {
            SCOPED_TRACE(::testing::Message() << "x span " << x_span << ", trial " << trial);
            const Cell<float, 3> cell = spread_cell<float, 3>(random, 1000, x_span);
            const auto swept = run_check<float, 3>([&](auto& report, auto& out) {
                cell_pairs.check_by_sweep(std::span<const std::uint32_t>(cell.entries),
                                          std::span<const Box<float, 3>>(cell.boxes), std::span<const BoxId>(cell.ids),
                                          cell.floor, report, out);
            });
            EXPECT_EQ(swept.pairs, expected_pairs(cell));
            EXPECT_EQ(swept.reports, swept.pairs.size()) << "a pair reported twice";
            EXPECT_EQ(cell_pairs.swept_long_rows(), x_span < 100.0) << "the turn the rows' reach asks for";
        }
    }
}

// The sort on x takes its bucket range from the lowest and highest keys (CellXOrder::sort), so
// the float of a key must be the float it came from, or below a double it came from.
TEST(MonotoneKey, FloatOfKeyUndoesTheKeyAndStaysAtOrBelowADouble) {
    const float floats[] = {0.0F,
                            -0.0F,
                            1.0F,
                            -1.0F,
                            1e-40F,
                            -1e-40F,
                            3.0e38F,
                            -3.0e38F,
                            std::numeric_limits<float>::max(),
                            -std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity()};
    for (const float x : floats) {
        EXPECT_EQ(float_of_key(monotone_key(x)), x + 0.0F) << x;  // -0 keys as +0
        EXPECT_FALSE(std::signbit(float_of_key(monotone_key(x))) && x == 0.0F) << "-0 keys as +0";
    }
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> any(-1e6, 1e6);
    for (int i = 0; i < 10000; ++i) {
        const double x = i % 100 == 0 ? -1e300 : any(random);
        const float below = float_of_key(monotone_key(x));
        EXPECT_LE(static_cast<double>(below), x) << x;
        if (x >= -static_cast<double>(std::numeric_limits<float>::max())) {
            EXPECT_GT(static_cast<double>(std::nextafter(below, std::numeric_limits<float>::infinity())), x) << x;
        }
        EXPECT_LE(below, to_float(x)) << "at or below the rounded coordinate the buckets take";
    }
}

TEST(CellPairs, DoubleGapsBelowFloatPrecisionAreTestedExactly) {
    // Floats round these boxes onto one another; only the exact test on the doubles tells the
    // touching pair (reported) from the ones a hair apart (not).
    const double base = 1.0e6;
    const double hair = 1.0e-7;  // far below a float's spacing at 1e6 (0.0625)
    std::vector<Box<double, 3>> boxes;
    for (int i = 0; i < 40; ++i) {
        const double x = base + i * 2 * hair;
        boxes.push_back(Box<double, 3>{{x, 0.0, 0.0}, {x + hair * 0.5, 1.0, 1.0}});
    }
    boxes.push_back(Box<double, 3>{{base + hair * 0.5, 0.0, 0.0}, {base + hair, 1.0, 1.0}});  // touches box 0 only
    std::vector<std::uint32_t> entries(boxes.size());
    for (std::uint32_t i = 0; i < entries.size(); ++i) entries[i] = i;
    std::vector<BoxId> ids(entries.begin(), entries.end());
    const CellFloor<double, 3> floor{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity()};
    CellPairs<double, 3> cell_pairs;
    for (const bool swept : {false, true}) {
        SCOPED_TRACE(swept ? "sweep" : "all pairs");
        PairSet pairs;
        BulkVector<std::uint32_t> home;
        auto report = [&](std::uint32_t a, std::uint32_t b) { pairs.insert(ordered(a, b)); };
        if (swept) {
            cell_pairs.check_by_sweep(std::span<const std::uint32_t>(entries), std::span<const Box<double, 3>>(boxes),
                                      std::span<const BoxId>(ids), floor, report, home);
        } else {
            cell_pairs.check_all_pairs(std::span<const std::uint32_t>(entries), std::span<const Box<double, 3>>(boxes),
                                       floor, report, home);
        }
        EXPECT_EQ(pairs, (PairSet{{0U, 40U}}));
        EXPECT_EQ(home.size(), boxes.size());
    }
}

}  // namespace
}  // namespace smb::detail

namespace smb::detail {
namespace {

/// append_set_lanes<Lanes> for every pattern of lane bits: the set lanes' values, in lane order,
/// and the end just past them. Runs the eight lanes only where they can run (AVX2).
// The scratch of a cell (src/cuts/cell_scratch.hpp): every array on a cache line of its own, none
// overlapping another, the hit list after the columns; and for a usual cell (up to 80 boxes,
// 256 hits) no hit shares its place modulo 4 KiB with what the pair test's rows load
// (the lower-corner bits and the coordinates), so that no store of a hit holds up those loads.
template <int Dim>
void expect_scratch_laid_out(std::size_t rows, std::size_t hit_room, CellScratch<Dim>& scratch) {
    SCOPED_TRACE(::testing::Message() << "Dim " << Dim << ", rows " << rows << ", hits " << hit_room);
    const auto columns = scratch.lay_out_for(rows, hit_room);
    auto at = [](const void* pointer) { return reinterpret_cast<std::uintptr_t>(pointer); };
    std::vector<std::pair<std::uintptr_t, std::uintptr_t>> ranges;  // [first, last) bytes
    std::vector<std::pair<std::uintptr_t, std::uintptr_t>> loaded;  // what the rows load
    auto add = [&](const void* first, std::size_t words, bool rows_load) {
        EXPECT_EQ(at(first) % 64, 0U) << "an array off its cache line";
        ranges.emplace_back(at(first), at(first) + 4 * words);
        if (rows_load) loaded.emplace_back(at(first), at(first) + 4 * words);
    };
    add(columns.position, rows, false);
    add(columns.key, rows, false);
    add(columns.inside, rows, true);
    for (int k = 0; k < Dim; ++k) {
        add(columns.min[static_cast<std::size_t>(k)], rows, true);
        add(columns.max[static_cast<std::size_t>(k)], rows, true);
    }
    for (std::size_t a = 0; a < ranges.size(); ++a) {
        EXPECT_GE(at(columns.hits), ranges[a].second) << "the hits start before a column ends";
        for (std::size_t b = a + 1; b < ranges.size(); ++b)
            EXPECT_TRUE(ranges[a].second <= ranges[b].first || ranges[b].second <= ranges[a].first) << "arrays overlap";
    }
    // Writable end to end: a sanitizer build would catch a buffer too small for them.
    std::fill_n(columns.hits, hit_room, 0xFFFFFFFFU);
    for (const auto& range : ranges) std::fill_n(reinterpret_cast<std::uint32_t*>(range.first), rows, 0U);
    const std::uintptr_t base = at(columns.position);
    EXPECT_EQ(base % 4096, 0U) << "the layout does not start on a 4 KiB boundary";
    const std::size_t usual_hits = std::min<std::size_t>(hit_room, 256);
    if (rows <= 88) {
        for (std::uintptr_t hit = at(columns.hits); hit < at(columns.hits + usual_hits); hit += 4) {
            for (const auto& range : loaded) {
                for (std::uintptr_t load = range.first; load < range.second; load += 4)
                    ASSERT_NE((hit - base) % 4096, (load - base) % 4096) << "a hit aliases a loaded column";
            }
        }
    }
}

TEST(CellScratch, ColumnsAndHitsApartOnTheirOwnLinesAndNotAliasedModulo4KiB) {
    CellScratch<3> scratch3;  // one object throughout: it grows and is laid out again
    CellScratch<2> scratch2;
    for (const std::size_t m : {0, 1, 7, 24, 46, 64, 80, 100, 128, 300, 60}) {
        const std::size_t rows = m + 8;
        const std::size_t all_pairs = m * (m - (m > 0 ? 1 : 0)) / 2 + 8;
        expect_scratch_laid_out<3>(rows, all_pairs, scratch3);
        expect_scratch_laid_out<3>(rows, 0, scratch3);
        expect_scratch_laid_out<2>(rows, all_pairs, scratch2);
    }
}

template <std::size_t Lanes>
void expect_set_lanes_appended() {
    typename FloatLanes<Lanes>::Masks values{};
    for (std::size_t lane = 0; lane < Lanes; ++lane) values[lane] = static_cast<std::int32_t>(100 + 7 * lane);
    for (unsigned bits = 0; bits < (1U << Lanes); ++bits) {
        SCOPED_TRACE(::testing::Message() << "lanes " << Lanes << ", bits " << bits);
        std::vector<std::uint32_t> out(2 + 2 * Lanes, 0xDEADBEEFU);
        std::vector<std::uint32_t> expected;
        for (std::size_t lane = 0; lane < Lanes; ++lane) {
            if ((bits >> lane & 1U) != 0) expected.push_back(static_cast<std::uint32_t>(values[lane]));
        }
        std::uint32_t* end = append_set_lanes<Lanes>(out.data() + 1, bits, values);
        ASSERT_EQ(end, out.data() + 1 + expected.size());
        EXPECT_TRUE(std::equal(expected.begin(), expected.end(), out.begin() + 1));
        EXPECT_EQ(out.front(), 0xDEADBEEFU) << "wrote before its start";
        EXPECT_TRUE(std::all_of(out.begin() + 1 + Lanes, out.end(), [](std::uint32_t v) { return v == 0xDEADBEEFU; }))
            << "wrote past its lanes";
    }
}

TEST(CellPairs, AppendSetLanesPacksTheSetLanesInLaneOrder) {
    expect_set_lanes_appended<4>();
#if SMB_LANES_AVX2
    if (cpu_has_avx2()) expect_set_lanes_appended<8>();
#else
    expect_set_lanes_appended<8>();
#endif
}

}  // namespace
}  // namespace smb::detail
