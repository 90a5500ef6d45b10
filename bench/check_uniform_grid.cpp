// SPDX-License-Identifier: MIT
// smb_check_uniform_grid: the comparison's uniform grid (peers/uniform_grid.hpp) against testing
// every pair, on inputs that stress its exactness: boxes touching on integer coordinates (so
// on cell borders), flat boxes and points, coordinates far from the origin, a few boxes far
// larger than the rest (the oversized path and its nested grid), and ids spread over 64 bits.
// Every call reuses the same grid, as the peer does from step to step. Exit status 1 on a
// difference.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "peers/peer.hpp"
#include "peers/uniform_grid.hpp"

namespace smb::bench {
namespace {

enum class Layout { touching, mixed_sizes, far_from_origin, flat_and_points };

template <int Dim>
void make_boxes(std::mt19937_64& rng, std::size_t count, Layout layout, std::vector<BenchBox<Dim>>& boxes,
                std::vector<BoxId>& ids) {
    boxes.resize(count);
    ids.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        // Distinct ids over the whole 64-bit range: a counter in the low bits.
        ids[i] = (rng() << 20) | i;
        for (int k = 0; k < Dim; ++k) {
            float low = 0, extent = 0;
            switch (layout) {
                case Layout::touching:
                    low = static_cast<float>(rng() % 20);
                    extent = static_cast<float>(rng() % 3);
                    break;
                case Layout::mixed_sizes:
                    low = static_cast<float>(rng() % 1000) * 0.1f;
                    extent = rng() % 50 == 0 ? static_cast<float>(rng() % 40) : static_cast<float>(rng() % 10) * 0.1f;
                    break;
                case Layout::far_from_origin:
                    low = 1e6f + static_cast<float>(rng() % 100) * 0.0625f;
                    extent = static_cast<float>(rng() % 16) * 0.0625f;
                    break;
                case Layout::flat_and_points:
                    low = -50.0f + static_cast<float>(rng() % 100);
                    extent = rng() % 4 == 0 ? 1.0f : 0.0f;
                    break;
            }
            boxes[i].min[k] = low;
            boxes[i].max[k] = low + extent;
        }
    }
}

template <int Dim>
int check(std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    UniformGrid<Dim> grid;
    std::vector<BenchBox<Dim>> boxes;
    std::vector<BoxId> ids;
    std::vector<Pair> expected, found;
    int failures = 0;
    for (const std::size_t count : {std::size_t{10}, std::size_t{70}, std::size_t{600}, std::size_t{2000}}) {
        for (const Layout layout :
             {Layout::touching, Layout::mixed_sizes, Layout::far_from_origin, Layout::flat_and_points}) {
            make_boxes<Dim>(rng, count, layout, boxes, ids);
            expected.clear();
            for (std::size_t i = 0; i < count; ++i)
                for (std::size_t j = i + 1; j < count; ++j)
                    if (overlaps(boxes[i], boxes[j])) expected.push_back(ordered_pair(ids[i], ids[j]));
            found.clear();
            grid.find_pairs(boxes, ids, found);
            std::sort(expected.begin(), expected.end());
            std::sort(found.begin(), found.end());
            if (found != expected) {
                std::printf("%dD seed %llu, %zu boxes, layout %d: %zu pairs, expected %zu\n", Dim,
                            static_cast<unsigned long long>(seed), count, static_cast<int>(layout), found.size(),
                            expected.size());
                ++failures;
            }
        }
    }
    return failures;
}

}  // namespace
}  // namespace smb::bench

int main() {
    int failures = 0;
    for (std::uint64_t seed = 1; seed <= 20; ++seed)
        failures += smb::bench::check<2>(seed) + smb::bench::check<3>(seed);
    std::printf("uniform grid against every pair: %d difference(s)\n", failures);
    return failures == 0 ? 0 : 1;
}
