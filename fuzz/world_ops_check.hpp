// SPDX-License-Identifier: MIT
#pragma once
// Sequences of World operations on arbitrary coordinates, checked against a mirror model: the
// check behind the fuzz_world_ops target and behind the replay of its inputs in the tests.
//
// The input is decoded into a world type (2D/3D, float/double), settings (cell population,
// chunk size, pair limit) and then a list of operations: insert (one or many), remove (one or
// many), update (one or many), assign, detect (into a vector or a sink), clear, and collision
// filters and static flags (one or many). Coordinates
// come from a table of hostile values (denormals, the largest finite values, infinities, NaN,
// -0.0, ...), from a small integer grid (so that boxes touch and share coordinates), or raw
// bytes. The model is a std::map from id to box, with each id's filter and static flag; it
// predicts which calls must be rejected and which pairs the filters let through.
// After every detection the pairs must equal brute force over the model; after every rejected
// call the world must be unchanged (size, every box, and the next detection).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "operation_input.hpp"
#include "smb/errors.hpp"
#include "smb/filter.hpp"
#include "smb/world.hpp"
#include "world_events_queries_check.hpp"

namespace smb::fuzz {

namespace world_ops_detail {

/// Which rejections a call may legitimately give, as bits.
enum Rejection : unsigned {
    kNone = 0,
    kInvalidBox = 1,
    kUnknownId = 2,
    kDuplicateId = 4,
    kArgument = 8,
};

template <typename Real, int Dim>
class Harness {
public:
    using World = smb::World<Real, Dim>;
    using BoxT = smb::Box<Real, Dim>;
    using Model = std::map<smb::BoxId, BoxT>;

    explicit Harness(const smb::WorldSettings& settings) : world_(settings) {}

    void run(ByteReader& in) {
        while (!in.done()) step(in);
        detect_and_compare(false);
    }

private:
    void step(ByteReader& in) {
        switch (in.byte() % 11) {
            case 0:
            case 1:
                insert_one(in);
                break;
            case 2:
                insert_many(in);
                break;
            case 3:
                remove_one(in);
                break;
            case 4:
                remove_many(in);
                break;
            case 5:
                update_one(in);
                break;
            case 6:
                update_many(in);
                break;
            case 7:
                assign(in);
                break;
            case 8:
                detect_and_compare(in.byte() % 2 == 1);
                break;
            case 9:
                if (in.byte() % 8 == 0) {
                    world_.clear();
                    events_model_.note_cleared();
                    model_.clear();
                    filters_.clear();
                    statics_.clear();
                }
                break;
            case 10:
                filter_or_static(in);
                break;
        }
    }

    /// A few bits, so that categories and masks meet and miss; sometimes every bit.
    static std::uint32_t decode_bits(ByteReader& in) {
        const std::uint8_t value = in.byte();
        return value >= 240 ? ~std::uint32_t{0} : value % 4;
    }

    void filter_or_static(ByteReader& in) {
        const std::uint8_t what = in.byte() % 4;
        if (what == 0) {
            const smb::BoxId id = pick_id(in);
            const smb::Filter filter{decode_bits(in), decode_bits(in)};
            const unsigned expected = model_.count(id) != 0 ? kNone : kUnknownId;
            attempt(expected, [&] { world_.set_filter(id, filter); });
            if (expected == kNone) filters_[id] = filter;
        } else if (what == 1) {
            const std::size_t count = in.byte() % 5;
            std::vector<smb::BoxId> ids;
            std::vector<smb::Filter> filters;
            unsigned expected = kNone;
            for (std::size_t i = 0; i < count; ++i) {
                ids.push_back(pick_id(in));
                filters.push_back(smb::Filter{decode_bits(in), decode_bits(in)});
                if (model_.count(ids.back()) == 0) expected |= kUnknownId;
            }
            if (in.byte() % 16 == 0) {
                filters.push_back(smb::Filter{});
                expected |= kArgument;
            }
            attempt(expected, [&] { world_.set_filter(ids, filters); });
            if (expected == kNone)
                for (std::size_t i = 0; i < count; ++i) filters_[ids[i]] = filters[i];
        } else {
            const smb::BoxId id = pick_id(in);
            const bool make_static = what == 2;
            const unsigned expected = model_.count(id) != 0 ? kNone : kUnknownId;
            attempt(expected, [&] { world_.set_static(id, make_static); });
            if (expected == kNone) {
                if (make_static)
                    statics_.insert(id);
                else
                    statics_.erase(id);
            }
        }
    }

    /// A box removed forgets its filter and static flag.
    void forget(smb::BoxId id) {
        events_model_.note_removed(id);
        model_.erase(id);
        filters_.erase(id);
        statics_.erase(id);
    }

    [[nodiscard]] smb::Filter filter_of(smb::BoxId id) const {
        const auto it = filters_.find(id);
        return it == filters_.end() ? smb::Filter{} : it->second;
    }

    [[nodiscard]] bool paired(smb::BoxId a, smb::BoxId b) const {
        if (statics_.count(a) != 0 && statics_.count(b) != 0) return false;
        const smb::Filter fa = filter_of(a);
        const smb::Filter fb = filter_of(b);
        return (fa.category & fb.mask) != 0 && (fb.category & fa.mask) != 0;
    }

    void insert_one(ByteReader& in) {
        const smb::BoxId id = decode_id(in);
        const BoxT box = decode_box<Real, Dim>(in);
        unsigned expected = kNone;
        if (!smb::is_valid(box)) expected |= kInvalidBox;
        if (model_.count(id) != 0) expected |= kDuplicateId;
        if (expected == kNone && model_.size() >= kMaxBoxes) return;
        attempt(expected, [&] { world_.insert(id, box); });
        if (expected == kNone) model_[id] = box;
    }

    void insert_many(ByteReader& in) {
        const std::size_t count = in.byte() % 9;
        std::vector<smb::BoxId> ids;
        std::vector<BoxT> boxes;
        unsigned expected = kNone;
        std::set<smb::BoxId> seen;
        for (std::size_t i = 0; i < count; ++i) {
            ids.push_back(decode_id(in));
            boxes.push_back(decode_box<Real, Dim>(in));
            if (!smb::is_valid(boxes.back())) expected |= kInvalidBox;
            if (model_.count(ids.back()) != 0 || !seen.insert(ids.back()).second) expected |= kDuplicateId;
        }
        if (in.byte() % 16 == 0) {
            boxes.push_back(BoxT{});
            expected |= kArgument;
        }
        if (expected == kNone && model_.size() + count > kMaxBoxes) return;
        attempt(expected, [&] { world_.insert(ids, boxes); });
        if (expected == kNone)
            for (std::size_t i = 0; i < count; ++i) model_[ids[i]] = boxes[i];
    }

    void remove_one(ByteReader& in) {
        const smb::BoxId id = pick_id(in);
        const unsigned expected = model_.count(id) != 0 ? kNone : kUnknownId;
        attempt(expected, [&] { world_.remove(id); });
        if (expected == kNone) forget(id);
    }

    void remove_many(ByteReader& in) {
        const std::size_t count = in.byte() % 9;
        std::vector<smb::BoxId> ids;
        unsigned expected = kNone;
        std::set<smb::BoxId> seen;
        for (std::size_t i = 0; i < count; ++i) {
            ids.push_back(pick_id(in));
            if (model_.count(ids.back()) == 0) expected |= kUnknownId;
            if (!seen.insert(ids.back()).second) expected |= kDuplicateId;
        }
        attempt(expected, [&] { world_.remove(ids); });
        if (expected == kNone)
            for (const smb::BoxId id : ids) forget(id);
    }

    void update_one(ByteReader& in) {
        const smb::BoxId id = pick_id(in);
        const BoxT box = decode_box<Real, Dim>(in);
        unsigned expected = kNone;
        if (model_.count(id) == 0) expected |= kUnknownId;
        if (!smb::is_valid(box)) expected |= kInvalidBox;
        attempt(expected, [&] { world_.update(id, box); });
        if (expected == kNone) model_[id] = box;
    }

    void update_many(ByteReader& in) {
        const std::size_t count = in.byte() % 9;
        std::vector<smb::BoxId> ids;
        std::vector<BoxT> boxes;
        unsigned expected = kNone;
        std::set<smb::BoxId> seen;
        for (std::size_t i = 0; i < count; ++i) {
            ids.push_back(pick_id(in));
            boxes.push_back(decode_box<Real, Dim>(in));
            if (model_.count(ids.back()) == 0) expected |= kUnknownId;
            if (!smb::is_valid(boxes.back())) expected |= kInvalidBox;
            if (!seen.insert(ids.back()).second) expected |= kDuplicateId;
        }
        if (in.byte() % 16 == 0 && !ids.empty()) {
            ids.pop_back();
            expected |= kArgument;
        }
        // An id named twice in one update is the one fault the library's documents disagree
        // on (errors.hpp names it a DuplicateIdError, the world applies the last box), so both
        // outcomes are allowed; either must be all or nothing.
        if (expected == kDuplicateId) {
            if (attempt_either(kDuplicateId, [&] { world_.update(ids, boxes); })) return;
            expected = kNone;
        } else {
            attempt(expected, [&] { world_.update(ids, boxes); });
        }
        if (expected == kNone)
            for (std::size_t i = 0; i < ids.size(); ++i) model_[ids[i]] = boxes[i];
    }

    void assign(ByteReader& in) {
        const std::size_t count = in.byte() % 33;
        std::vector<BoxT> boxes;
        unsigned expected = kNone;
        for (std::size_t i = 0; i < count; ++i) {
            boxes.push_back(decode_box<Real, Dim>(in));
            if (!smb::is_valid(boxes.back())) expected |= kInvalidBox;
        }
        attempt(expected, [&] { world_.assign(boxes); });
        if (expected == kNone) {
            // Ids beyond the array are removed; the others keep their filters and flags.
            std::vector<smb::BoxId> gone;
            for (const auto& [id, box] : model_)
                if (id >= count) gone.push_back(id);
            for (const smb::BoxId id : gone) forget(id);
            for (std::size_t i = 0; i < count; ++i) model_[i] = boxes[i];
        }
    }

    /// Mostly an id the model holds, sometimes any id.
    smb::BoxId pick_id(ByteReader& in) {
        const std::uint8_t choice = in.byte();
        if (model_.empty() || choice >= 200) return decode_id(in);
        auto it = model_.begin();
        std::advance(it, static_cast<std::ptrdiff_t>(choice % model_.size()));
        return it->first;
    }

    /// The rejection `call` gave, as one bit; kNone if it returned.
    template <typename Call>
    static unsigned rejection_of(Call call) {
        try {
            call();
        } catch (const smb::InvalidBoxError&) {
            return kInvalidBox;
        } catch (const smb::UnknownIdError&) {
            return kUnknownId;
        } catch (const smb::DuplicateIdError&) {
            return kDuplicateId;
        } catch (const smb::ArgumentError&) {
            return kArgument;
        }
        return kNone;
    }

    template <typename Call>
    void attempt(unsigned expected, Call call) {
        const unsigned thrown = rejection_of(call);
        if (expected == kNone && thrown != kNone) broken_promise("a valid call was rejected");
        if (expected != kNone && thrown == kNone) broken_promise("an invalid call was accepted");
        if ((expected & thrown) != thrown) broken_promise("a call was rejected for a wrong reason");
        if (thrown != kNone) check_rejected_call_changed_nothing();
    }

    /// For a call that may be rejected for `allowed` or succeed; true if it was rejected.
    template <typename Call>
    bool attempt_either(unsigned allowed, Call call) {
        const unsigned thrown = rejection_of(call);
        if ((allowed & thrown) != thrown) broken_promise("a call was rejected for a wrong reason");
        if (thrown != kNone) check_rejected_call_changed_nothing();
        return thrown != kNone;
    }

    void check_rejected_call_changed_nothing() {
        check_unchanged();
        detect_and_compare(false);
    }

    void check_unchanged() const {
        if (world_.size() != model_.size()) broken_promise("a rejected call changed the size");
        for (const auto& [id, box] : model_) {
            if (!world_.contains(id)) broken_promise("a rejected call lost a box");
            const BoxT held = world_.box(id);
            if (!(held == box)) broken_promise("a rejected call changed a box");
            const smb::Filter filter = world_.filter(id);
            const smb::Filter expected = filter_of(id);
            if (filter.category != expected.category || filter.mask != expected.mask)
                broken_promise("a rejected call changed a filter");
            if (world_.is_static(id) != (statics_.count(id) != 0))
                broken_promise("a rejected call changed a static flag");
        }
    }

    void detect_and_compare(bool through_sink) {
        std::vector<smb::Pair> expected;
        for (auto a = model_.begin(); a != model_.end(); ++a)
            for (auto b = std::next(a); b != model_.end(); ++b)
                if (smb::overlaps(a->second, b->second) && paired(a->first, b->first))
                    expected.push_back({a->first, b->first});

        // Into a vector, with events; a detection over the pair limit throws and completes nothing.
        bool completed = false;
        check_detection(expected, world_.settings(), through_sink, [&](auto& pairs_or_sink) {
            if constexpr (std::is_same_v<std::decay_t<decltype(pairs_or_sink)>, std::vector<smb::Pair>>)
                world_.detect(pairs_or_sink, events_);
            else
                world_.detect(pairs_or_sink);
            completed = true;
        });
        if (!completed) return;
        if (through_sink) {
            events_model_.forget_removals();
            return;
        }
        events_model_.check(events_, expected, [&](smb::BoxId id) { return model_.count(id) != 0; });
        check_queries(world_, model_);
    }

    World world_;
    smb::PairEvents events_;
    EventsModel events_model_;
    Model model_;
    std::map<smb::BoxId, smb::Filter> filters_;
    std::set<smb::BoxId> statics_;
};

/// Decodes what every operations input starts with — the type (2D/3D, float/double) and the
/// settings (cell population, chunk size, pair limit) — and runs Checker<Real, Dim> on the rest.
template <template <typename, int> class Checker>
void run_decoded(const std::uint8_t* data, std::size_t size) {
    ByteReader in(data, size);
    const std::uint8_t kind = in.byte();
    smb::WorldSettings settings;
    settings.target_cell_population = 1 + in.byte() % 32;
    settings.pair_chunk_size = 1 + in.byte() % 8;
    const std::uint8_t limit = in.byte();
    if (limit < 64) settings.max_pairs_held = limit;
    switch (kind % 4) {
        case 0:
            Checker<float, 2>(settings).run(in);
            break;
        case 1:
            Checker<double, 2>(settings).run(in);
            break;
        case 2:
            Checker<float, 3>(settings).run(in);
            break;
        default:
            Checker<double, 3>(settings).run(in);
            break;
    }
}

}  // namespace world_ops_detail

/// Decodes `data` into a world, settings and operations and checks every operation; throws
/// std::logic_error at the first broken promise of smb.
inline void check_world_operations(const std::uint8_t* data, std::size_t size) {
    world_ops_detail::run_decoded<world_ops_detail::Harness>(data, size);
}

}  // namespace smb::fuzz
