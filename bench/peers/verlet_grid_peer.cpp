// SPDX-License-Identifier: MIT
// A grid with a Verlet skin, as molecular dynamics codes (LAMMPS's neighbour lists) do it: each
// box is fattened by the skin on every side, and the list of pairs whose fat boxes overlap is
// built with the uniform grid (peers/uniform_grid.hpp), its boxes renumbered in cell order. While
// every box stays inside its fat box, a pair of boxes that overlap has overlapping fat boxes, so
// it is in the list: a step then only writes the current boxes into 32-byte records (3D) in that
// order and tests the listed pairs. A box that leaves its fat box, or too many insertions or
// removals since the list was built, rebuild it; a box inserted in between gets its candidates
// from the grid of the last build and from the boxes inserted after it.

#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "peers/peer_factories.hpp"
#include "peers/uniform_grid.hpp"

namespace smb::bench {
namespace {

// The list is rebuilt when the boxes inserted or removed since its build exceed these shares.
constexpr std::size_t rebuild_after_inserted_share = 64;  // 1/64 of the boxes
constexpr std::size_t rebuild_after_removed_share = 16;   // 1/16
constexpr std::uint32_t no_slot = std::numeric_limits<std::uint32_t>::max();
// Positions of the scene's arrays read ahead of the one written.
constexpr std::size_t prefetch_ahead = 16;

template <int Dim>
class VerletGridPeer final : public Peer<Dim> {
public:
    explicit VerletGridPeer(float skin) : skin_(skin) {}

    void build(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        records_.clear();
        fat_.clear();
        slot_of_id_.clear();
        for (std::size_t i = 0; i < step.size(); ++i) append(step.boxes[i], step.ids[i]);
        rebuild();
        test_candidates(pairs);
    }

    void step(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        for (const BoxId id : step.removed_ids) remove(id);
        const bool escaped = move(step);
        for (std::size_t i = step.first_inserted; i < step.size(); ++i) insert(step.boxes[i], step.ids[i]);
        if (escaped || inserted_ * rebuild_after_inserted_share > records_.size() ||
            removed_ * rebuild_after_removed_share > records_.size())
            rebuild();
        test_candidates(pairs);
    }

    [[nodiscard]] std::string details_json() const override {
        std::ostringstream json;
        json << "\"verlet_skin\":" << skin_ << ",\"verlet_rebuilds\":" << rebuilds_
             << ",\"verlet_candidates\":" << candidates_.size() << ",\"grid_lanes\":" << grid_.lanes();
        return json.str();
    }

private:
    /// A box as the candidate tests read it: 32 bytes in 3D. A removed box's record has
    /// min = +inf and max = -inf, so that it overlaps nothing and fits in any fat box.
    struct alignas(Dim == 3 ? 32 : 8) Record {
        std::array<float, Dim> min;
        std::array<float, Dim> max;
        BoxId id;
    };
    using PositionPair = typename UniformGrid<Dim>::PositionPair;

    [[nodiscard]] BenchBox<Dim> fattened(const BenchBox<Dim>& box) const noexcept {
        BenchBox<Dim> fat;
        for (int k = 0; k < Dim; ++k) {
            fat.min[k] = box.min[k] - skin_;
            fat.max[k] = box.max[k] + skin_;
        }
        return fat;
    }
    static Record record_of(const BenchBox<Dim>& box, BoxId id) noexcept { return Record{box.min, box.max, id}; }
    static bool overlap(const Record& a, const Record& b) noexcept {
        bool result = true;
        for (int k = 0; k < Dim; ++k) result &= (a.min[k] <= b.max[k]) & (b.min[k] <= a.max[k]);
        return result;
    }
    static bool inside(const Record& box, const BenchBox<Dim>& fat) noexcept {
        bool result = true;
        for (int k = 0; k < Dim; ++k) result &= (box.min[k] >= fat.min[k]) & (box.max[k] <= fat.max[k]);
        return result;
    }

    std::uint32_t& slot_of(BoxId id) {
        if (id >= slot_of_id_.size()) {
            // The scenes number their boxes with a counter: a table indexed by id stays small.
            if (id > 64 * (records_.size() + 1024)) throw std::invalid_argument("verlet_grid needs dense box ids");
            slot_of_id_.resize(static_cast<std::size_t>(id) + 1 + slot_of_id_.size() / 2, no_slot);
        }
        return slot_of_id_[id];
    }

    void append(const BenchBox<Dim>& box, BoxId id) {
        slot_of(id) = static_cast<std::uint32_t>(records_.size());
        records_.push_back(record_of(box, id));
        fat_.push_back(fattened(box));
    }

    void remove(BoxId id) {
        std::uint32_t& slot = slot_of(id);
        Record& record = records_[slot];
        record.min.fill(std::numeric_limits<float>::infinity());
        record.max.fill(-std::numeric_limits<float>::infinity());
        slot = no_slot;
        ++removed_;
    }

    // The survivors' new boxes into their records; true when one left its fat box.
    bool move(const SceneStep<Dim>& step) {
        bool escaped = false;
        const std::uint32_t* slots = slot_of_id_.data();
        for (std::size_t i = 0; i < step.first_inserted; ++i) {
            if (i + prefetch_ahead < step.first_inserted) {
                const std::uint32_t ahead = slots[step.ids[i + prefetch_ahead]];
                __builtin_prefetch(&records_[ahead], 1);
                __builtin_prefetch(&fat_[ahead]);
            }
            const std::uint32_t slot = slots[step.ids[i]];
            records_[slot] = record_of(step.boxes[i], step.ids[i]);
            escaped |= !inside(records_[slot], fat_[slot]);
        }
        return escaped;
    }

    // Candidates from the grid of the last build, and from every box inserted since.
    void insert(const BenchBox<Dim>& box, BoxId id) {
        const BenchBox<Dim> fat = fattened(box);
        const auto slot = static_cast<std::uint32_t>(records_.size());
        found_.clear();
        grid_.find_overlapping(fat, found_);
        for (std::uint32_t other = built_count_; other < slot; ++other)
            if (overlaps(fat, fat_[other])) found_.push_back(other);
        for (const std::uint32_t other : found_) candidates_.push_back(PositionPair{other, slot});
        append(box, id);
        ++inserted_;
    }

    // The live boxes renumbered in the grid's cell order, and the pairs of their fat boxes.
    void rebuild() {
        live_fat_.clear();
        live_records_.clear();
        for (std::size_t slot = 0; slot < records_.size(); ++slot) {
            if (records_[slot].min[0] > records_[slot].max[0]) continue;  // removed
            live_records_.push_back(records_[slot]);
            live_fat_.push_back(fattened(BenchBox<Dim>{records_[slot].min, records_[slot].max}));
        }
        candidates_.clear();
        grid_.find_position_pairs(live_fat_, candidates_);
        const auto order = grid_.order();
        records_.resize(order.size());
        fat_.resize(order.size());
        for (std::size_t p = 0; p < order.size(); ++p) {
            records_[p] = live_records_[order[p]];
            fat_[p] = live_fat_[order[p]];
            slot_of_id_[records_[p].id] = static_cast<std::uint32_t>(p);
        }
        built_count_ = static_cast<std::uint32_t>(records_.size());
        inserted_ = removed_ = 0;
        ++rebuilds_;
    }

    // Branch-free: every candidate writes its index, and only a hit moves the end on.
    void test_candidates(std::vector<Pair>& pairs) {
        pairs.clear();
        hits_.resize(candidates_.size());
        std::uint32_t* out = hits_.data();
        const Record* records = records_.data();
        const std::size_t count = candidates_.size();
        for (std::size_t c = 0; c < count; ++c) {
            // The partner of a box lies up to two planes of cells ahead: not always in cache.
            if (c + prefetch_ahead < count) __builtin_prefetch(&records[candidates_[c + prefetch_ahead].b]);
            *out = static_cast<std::uint32_t>(c);
            out += overlap(records[candidates_[c].a], records[candidates_[c].b]);
        }
        for (const std::uint32_t* hit = hits_.data(); hit != out; ++hit) {
            const BoxId a = records[candidates_[*hit].a].id, b = records[candidates_[*hit].b].id;
            pairs.push_back(Pair{std::min(a, b), std::max(a, b)});
        }
    }

    float skin_;
    UniformGrid<Dim> grid_;
    std::vector<Record> records_;  ///< by slot: cell order at the last build, inserted boxes after
    std::vector<BenchBox<Dim>> fat_;
    std::vector<std::uint32_t> slot_of_id_;
    std::vector<PositionPair> candidates_;
    std::vector<std::uint32_t> hits_;
    std::vector<std::uint32_t> found_;
    std::vector<Record> live_records_;
    std::vector<BenchBox<Dim>> live_fat_;
    std::uint32_t built_count_ = 0;
    std::size_t inserted_ = 0;
    std::size_t removed_ = 0;
    std::size_t rebuilds_ = 0;
};

}  // namespace

template <int Dim>
std::unique_ptr<Peer<Dim>> make_verlet_grid_peer(float skin) {
    return std::make_unique<VerletGridPeer<Dim>>(skin);
}

template std::unique_ptr<Peer<2>> make_verlet_grid_peer<2>(float);
template std::unique_ptr<Peer<3>> make_verlet_grid_peer<3>(float);

}  // namespace smb::bench
