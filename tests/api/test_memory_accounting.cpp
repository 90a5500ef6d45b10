// SPDX-License-Identifier: MIT
// Checks World::bytes_held() and DetectStats::bytes_held against the heap bytes the world
// really holds, measured by replacing the global allocation functions of this test program.
// Agreement is asked within kRelativeTolerance of the measured bytes plus kSlackBytes. The same
// count of allocations shows that a World's query index is not built again while its boxes stay,
// and the peak of the live bytes that a Detector whose boxes grow never holds an array's old
// block beside its new one.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

#include "reference/random_boxes.hpp"
#include "reference/world_types.hpp"
#include "smb/detector.hpp"
#include "smb/world.hpp"

namespace {

// Every allocation carries a header with its requested size, so that frees can be counted
// without relying on malloc_usable_size (which includes the allocator's rounding).
constexpr std::size_t kHeader = 64;  // covers every alignment the program asks for
std::atomic<std::int64_t> g_live_bytes{0};
std::atomic<std::int64_t> g_peak_bytes{0};
std::atomic<std::int64_t> g_allocations{0};

void* counted_allocate(std::size_t size, std::size_t alignment) {
    const std::size_t header = alignment > kHeader ? alignment : kHeader;
    void* raw = std::aligned_alloc(header, ((size + header + header - 1) / header) * header);
    if (raw == nullptr) throw std::bad_alloc();
    auto* bytes = static_cast<unsigned char*>(raw);
    auto* user = bytes + header;
    reinterpret_cast<std::size_t*>(user)[-1] = size;
    reinterpret_cast<std::size_t*>(user)[-2] = header;
    const std::int64_t live = g_live_bytes.fetch_add(static_cast<std::int64_t>(size), std::memory_order_relaxed) +
                              static_cast<std::int64_t>(size);
    std::int64_t peak = g_peak_bytes.load(std::memory_order_relaxed);
    while (live > peak && !g_peak_bytes.compare_exchange_weak(peak, live, std::memory_order_relaxed)) {}
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    return user;
}

void counted_free(void* pointer) noexcept {
    if (pointer == nullptr) return;
    auto* user = static_cast<unsigned char*>(pointer);
    const std::size_t size = reinterpret_cast<std::size_t*>(user)[-1];
    const std::size_t header = reinterpret_cast<std::size_t*>(user)[-2];
    g_live_bytes.fetch_sub(static_cast<std::int64_t>(size), std::memory_order_relaxed);
    std::free(user - header);
}

std::int64_t live_bytes() { return g_live_bytes.load(std::memory_order_relaxed); }
std::int64_t allocations() { return g_allocations.load(std::memory_order_relaxed); }
/// The most bytes live since the last call, which starts the count again from the bytes live now.
std::int64_t take_peak_bytes() { return g_peak_bytes.exchange(live_bytes(), std::memory_order_relaxed); }

}  // namespace

void* operator new(std::size_t size) { return counted_allocate(size, alignof(std::max_align_t)); }
void* operator new[](std::size_t size) { return counted_allocate(size, alignof(std::max_align_t)); }
void* operator new(std::size_t size, std::align_val_t alignment) {
    return counted_allocate(size, static_cast<std::size_t>(alignment));
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
    return counted_allocate(size, static_cast<std::size_t>(alignment));
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    try {
        return counted_allocate(size, alignof(std::max_align_t));
    } catch (...) {
        return nullptr;
    }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
    try {
        return counted_allocate(size, alignof(std::max_align_t));
    } catch (...) {
        return nullptr;
    }
}
void operator delete(void* pointer) noexcept { counted_free(pointer); }
void operator delete[](void* pointer) noexcept { counted_free(pointer); }
void operator delete(void* pointer, std::size_t) noexcept { counted_free(pointer); }
void operator delete[](void* pointer, std::size_t) noexcept { counted_free(pointer); }
void operator delete(void* pointer, std::align_val_t) noexcept { counted_free(pointer); }
void operator delete[](void* pointer, std::align_val_t) noexcept { counted_free(pointer); }
void operator delete(void* pointer, std::size_t, std::align_val_t) noexcept { counted_free(pointer); }
void operator delete[](void* pointer, std::size_t, std::align_val_t) noexcept { counted_free(pointer); }
void operator delete(void* pointer, const std::nothrow_t&) noexcept { counted_free(pointer); }
void operator delete[](void* pointer, const std::nothrow_t&) noexcept { counted_free(pointer); }

namespace smb::test {
namespace {

constexpr double kRelativeTolerance = 0.10;
constexpr std::int64_t kSlackBytes = 16 * 1024;

template <typename WorldType>
class MemoryAccountingTest : public ::testing::Test {
protected:
    using Real = typename WorldType::real_type;
    static constexpr int Dim = WorldType::dimension;
    using BoxT = Box<Real, Dim>;

    /// Compares the world's own account with the bytes allocated since `baseline` and still
    /// live: everything the test itself holds was allocated before the baseline.
    static void expect_agreement(const char* when, std::size_t reported, std::int64_t baseline, std::size_t boxes) {
        const std::int64_t measured = live_bytes() - baseline;
        const auto claimed = static_cast<std::int64_t>(reported);
        const auto allowed =
            static_cast<std::int64_t>(kRelativeTolerance * static_cast<double>(measured)) + kSlackBytes;
        std::printf("%-34s boxes %7zu  measured %10lld B (%6.1f B/box)  reported %10lld B\n", when, boxes,
                    static_cast<long long>(measured),
                    boxes ? static_cast<double>(measured) / static_cast<double>(boxes) : 0.0,
                    static_cast<long long>(claimed));
        EXPECT_LE(claimed - measured, allowed) << when << ": reports more than it holds";
        EXPECT_LE(measured - claimed, allowed) << when << ": holds more than it reports";
    }

    void run(std::size_t count) {
        Random random(777);
        // Boxes with a side of 1..2 at density about 0.3, as in the paper's Section 4.1.
        const double space = Dim == 2 ? std::sqrt(static_cast<double>(count) * 2.25 / 0.3)
                                      : std::cbrt(static_cast<double>(count) * 3.375 / 0.3);
        std::vector<BoxId> ids(count);
        std::vector<BoxT> boxes(count);
        for (std::size_t i = 0; i < count; ++i) {
            ids[i] = 3 * i + 1;
            boxes[i] = random_box<Real, Dim>(random, 0, space, 1.0, 2.0);
        }
        const std::vector<BoxId> half(ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(count / 2));
        std::vector<Pair> pairs;
        pairs.reserve(count * 8);
        const auto pairs_bytes = static_cast<std::int64_t>(pairs.capacity() * sizeof(Pair));

        const std::int64_t baseline = live_bytes();
        auto world = std::make_unique<WorldType>(test_settings());
        world->insert(ids, boxes);
        expect_agreement("after insert", world->bytes_held(), baseline, world->size());
        for (int step = 0; step < 4; ++step) {
            for (auto& box : boxes) box = perturbed(random, box, 1e-3 * space, 1e-3);
            world->update(ids, boxes);
            const DetectStats stats = world->detect(pairs);
            ASSERT_LE(pairs.capacity() * sizeof(Pair), static_cast<std::size_t>(pairs_bytes))
                << "the pair list outgrew its reservation; raise it";
            expect_agreement("after detect (stats)", stats.bytes_held, baseline, world->size());
            expect_agreement("after detect (bytes_held)", world->bytes_held(), baseline, world->size());
        }
        // Remove half: the world may keep its capacity, but must still account for it.
        world->remove(half);
        const DetectStats stats = world->detect(pairs);
        expect_agreement("after removing half", stats.bytes_held, baseline, world->size());
        world->clear();
        expect_agreement("after clear", world->bytes_held(), baseline, world->size());
        world.reset();
        // GoogleTest keeps the text of any failure above on the heap, hence the slack.
        EXPECT_LE(live_bytes() - baseline, kSlackBytes) << "the destroyed world left bytes behind";
    }
};

TYPED_TEST_SUITE(MemoryAccountingTest, WorldTypes, WorldTypeNames);

TYPED_TEST(MemoryAccountingTest, BytesHeldMatchesTheHeap) { this->run(scaled(100000)); }

// A query builds the index (temporary arrays: allocations); detections, filters and statics
// leave the boxes as they were, so the queries after them reuse it and allocate nothing, while
// an update builds it again.
TYPED_TEST(MemoryAccountingTest, QueriesReuseTheIndexUntilTheBoxesChange) {
    Random random(5);
    std::vector<typename TestFixture::BoxT> boxes(2000);
    for (auto& box : boxes)
        box = random_box<typename TypeParam::real_type, TypeParam::dimension>(random, 0, 40, 0.5, 2.0);
    TypeParam world;
    world.assign(boxes);
    std::vector<BoxId> found;
    found.reserve(boxes.size());
    std::vector<Pair> pairs;
    world.query(boxes[0], found);
    const auto query_allocations = [&] {
        const std::int64_t before = allocations();
        world.query(boxes[1], found);
        return allocations() - before;
    };
    EXPECT_EQ(query_allocations(), 0);
    world.detect(pairs);
    EXPECT_EQ(query_allocations(), 0) << "a detection made the index rebuild";
    world.set_static(BoxId{3}, true);
    Filter filter;
    filter.category = 2;
    world.set_filter(BoxId{4}, filter);
    world.detect(pairs);
    EXPECT_EQ(query_allocations(), 0) << "filters and statics made the index rebuild";
    world.update(BoxId{5}, boxes[6]);
    EXPECT_GT(query_allocations(), 0) << "an update left the index as it was";
    EXPECT_EQ(query_allocations(), 0);
}

// A Detector whose boxes grow by a tenth grows every array that follows N in the next detection.
// Those arrays are written over whole by it, so each is freed before its larger block is taken,
// not copied into it: at no moment does the detection hold more than it holds after (growing by
// copying held the old copy of the boxes in cell order beside the new one, about 24 bytes a box
// more in 3D).
template <typename Real, int Dim>
void expect_growth_holds_no_old_block() {
    using BoxT = Box<Real, Dim>;
    const std::size_t count = scaled(40000);
    Random random(91);
    const double space = Dim == 2 ? std::sqrt(static_cast<double>(count) * 2.25 / 0.3)
                                  : std::cbrt(static_cast<double>(count) * 3.375 / 0.3);
    std::vector<BoxT> boxes(count + count / 10);
    for (auto& box : boxes) box = random_box<Real, Dim>(random, 0, space, 1.0, 2.0);
    std::vector<Pair> pairs;
    pairs.reserve(boxes.size() * 16);
    const std::int64_t baseline = live_bytes();
    Detector<Real, Dim> detector;
    const std::span<const BoxT> all(boxes);
    for (int step = 0; step < 3; ++step) {
        pairs.clear();
        detector.detect(all.first(count), pairs);
    }
    const std::size_t held_before = detector.bytes_held();
    (void)take_peak_bytes();
    pairs.clear();
    const DetectStats stats = detector.detect(all, pairs);
    ASSERT_LE(pairs.capacity(), boxes.size() * 16) << "the pair list outgrew its reservation; raise it";
    const std::int64_t peak = take_peak_bytes() - baseline;
    const auto held = static_cast<std::int64_t>(stats.bytes_held);
    std::printf("Detector<%s, %d>: held %zu -> %lld B, peak while growing %lld B\n",
                sizeof(Real) == 4 ? "float" : "double", Dim, held_before, static_cast<long long>(held),
                static_cast<long long>(peak));
    EXPECT_GT(stats.bytes_held, held_before + held_before / 20) << "the arrays did not grow: the test proves nothing";
    std::int64_t allowed = held + held / 20 + kSlackBytes;
#ifdef SMB_VALIDATE
    // The check of the lists after each detection counts every box's cells in an array of its own.
    allowed += static_cast<std::int64_t>(boxes.size() * sizeof(std::uint32_t));
#endif
    EXPECT_LE(peak, allowed) << "an array held its old block beside its new one";
}

TEST(PeakMemoryTest, AGrowingDetectorHoldsNoOldBlockBesideTheNew) {
    expect_growth_holds_no_old_block<float, 3>();
    expect_growth_holds_no_old_block<float, 2>();
    expect_growth_holds_no_old_block<double, 3>();
}

}  // namespace
}  // namespace smb::test
