// SPDX-License-Identifier: MIT
// smb_explosion: a pair explosion in the library, for docs/robustness.md. N identical boxes make
// N(N-1)/2 pairs (5·10^9 for N = 100 000). detect(sink) must stream them all in bounded memory,
// each once with a < b; detect(vector) must refuse with PairLimitError at max_pairs_held
// instead of exhausting memory. Prints times and resident memory; exit status 0 when both hold.
//
//   smb_explosion [boxes]   (default 100000)

#include <chrono>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <span>
#include <string>
#include <vector>

#include "process_memory.hpp"
#include "smb/world.hpp"

namespace {

using smb::soak::peak_resident_bytes;
using smb::soak::resident_bytes;

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
    const std::uint64_t box_count = argc > 1 ? std::stoull(argv[1]) : 100000;
    const std::uint64_t expected_pairs = box_count * (box_count - 1) / 2;
    smb::World3d world;
    world.assign(std::vector<smb::Box3d>(box_count, smb::Box3d{{0, 0, 0}, {1, 1, 1}}));
    std::cout << "boxes " << box_count << ", expected pairs " << expected_pairs << ", resident " << resident_bytes()
              << " bytes\n";

    // Streaming: count the pairs and check every one; a pair checksum catches repeats that a
    // count alone would not (a repeated pair and a missing one would cancel).
    std::uint64_t pairs_seen = 0;
    std::uint64_t bad_pairs = 0;
    std::uint64_t sum_of_a = 0;
    std::uint64_t sum_of_b = 0;
    auto start = std::chrono::steady_clock::now();
    world.detect([&](std::span<const smb::Pair> chunk) {
        pairs_seen += chunk.size();
        for (const smb::Pair& pair : chunk) {
            if (!(pair.a < pair.b) || pair.b >= box_count) ++bad_pairs;
            sum_of_a += pair.a;
            sum_of_b += pair.b;
        }
    });
    const double stream_s = seconds_since(start);
    // Over all pairs a < b of 0..N-1: sum of a is sum_a a (N-1-a), sum of b is sum_b b * b.
    std::uint64_t expected_sum_a = 0;
    std::uint64_t expected_sum_b = 0;
    for (std::uint64_t i = 0; i < box_count; ++i) {
        expected_sum_a += i * (box_count - 1 - i);
        expected_sum_b += i * i;
    }
    const bool stream_ok =
        pairs_seen == expected_pairs && bad_pairs == 0 && sum_of_a == expected_sum_a && sum_of_b == expected_sum_b;
    std::cout << "detect(sink): " << pairs_seen << " pairs in " << stream_s << " s ("
              << (stream_ok ? "all exact" : "WRONG") << "), resident " << resident_bytes() << " bytes, peak "
              << peak_resident_bytes() << " bytes\n";

    std::vector<smb::Pair> pairs;
    bool refused = false;
    start = std::chrono::steady_clock::now();
    try {
        world.detect(pairs);
    } catch (const smb::PairLimitError& error) {
        refused = true;
        std::cout << "detect(vector): PairLimitError after " << seconds_since(start) << " s: " << error.what()
                  << "\n  resident " << resident_bytes() << " bytes, peak " << peak_resident_bytes()
                  << " bytes, vector capacity " << pairs.capacity() << " pairs\n";
    }
    if (!refused) std::cout << "detect(vector): returned " << pairs.size() << " pairs\n";
    const bool vector_ok = refused == (expected_pairs > world.settings().max_pairs_held);
    return stream_ok && vector_ok ? 0 : 2;
}
