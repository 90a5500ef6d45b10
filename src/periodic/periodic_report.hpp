// SPDX-License-Identifier: MIT
#pragma once
// The report the pipeline calls with the pairs of gathered boxes it finds in a periodic
// detection (periodic_images.hpp): it turns each into a pair of the caller's boxes and their
// shift, or drops it. Two boxes gathered as they are (keys without kTranslatedKey) overlap
// exactly as the caller's boxes do, under the shift 0: reported at once, without reading memory
// where the keys hold the names. Any other pair is decoded to (source, mask) on both sides: the
// same source (a box and its own image, which never overlap in truth) and masks that share an
// axis (a repeat of a pair found without both images) are dropped; the rest are confirmed on the
// caller's boxes with overlaps_with_shift, since the gathered boxes were grown to cover the
// rounding of their translation.

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "periodic/periodic_images.hpp"
#include "smb/box.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"
#include "smb/periodic.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class PeriodicReport {
public:
    /// `names`: the name of each of the caller's boxes (a World's ids), or empty for its index.
    /// The pairs are appended to `out`, at most `limit` of them (else PairLimitError).
    PeriodicReport(const PeriodicImages<Real, Dim>& images, std::span<const Box<Real, Dim>> boxes,
                   std::span<const BoxId> names, const PeriodicDomain<Real, Dim>& domain,
                   std::vector<PeriodicPair>& out, std::size_t limit)
        : images_(images),
          boxes_(boxes),
          names_(names),
          domain_(domain),
          out_(out),
          limit_(limit),
          end_(out.size() + limit),
          packed_(images.packed()) {}

    void operator()(BoxId x, BoxId y) {
        if (((x | y) & kTranslatedKey) == 0) [[likely]] {
            emit(plain_name(x), plain_name(y), {});
            return;
        }
        const Side sx = side(x);
        const Side sy = side(y);
        if (sx.source == sy.source || (sx.mask & sy.mask) != 0) return;
        // y's shift relative to x: n_x - n_y + u - v on every periodic axis.
        std::array<std::int32_t, 3> shift{};
        for (int k = 0; k < Dim; ++k) {
            const auto ks = static_cast<std::size_t>(k);
            shift[ks] = sx.wrap[ks] - sy.wrap[ks] + static_cast<std::int32_t>((sx.mask >> k) & 1u) -
                        static_cast<std::int32_t>((sy.mask >> k) & 1u);
        }
        BoxId a = sx.name;
        BoxId b = sy.name;
        std::uint32_t first = sx.source;
        std::uint32_t second = sy.source;
        if (b < a) {
            std::swap(a, b);
            std::swap(first, second);
            for (auto& s : shift) s = -s;
        }
        if (!overlaps_with_shift(boxes_[first], boxes_[second], shift, domain_)) return;
        if (nearer_shift_overlaps(boxes_[first], boxes_[second], shift)) return;
        emit(a, b, shift);
    }

    void append(std::span<const Pair> pairs) {
        for (const Pair& p : pairs) (*this)(p.a, p.b);
    }

private:
    /// Whether the pair also overlaps under the shift one step nearer 0 on some axis. Only
    /// rounding allows two shifts (both extents within a few rounding steps of half the period),
    /// and then the one nearest 0 on every axis is the pair's: the pairs of untranslated boxes,
    /// reported with the shift 0 unchecked, keep theirs.
    [[nodiscard]] bool nearer_shift_overlaps(const Box<Real, Dim>& a, const Box<Real, Dim>& b,
                                             const std::array<std::int32_t, 3>& shift) const noexcept {
        for (int k = 0; k < Dim; ++k) {
            const auto ks = static_cast<std::size_t>(k);
            if (shift[ks] == 0) continue;
            std::array<std::int32_t, 3> nearer = shift;
            nearer[ks] += shift[ks] > 0 ? -1 : 1;
            if (overlaps_with_shift(a, b, nearer, domain_)) return true;
        }
        return false;
    }

    /// One box of a pair: the caller's box, its name, and how its gathered box was translated.
    struct Side {
        std::uint32_t source;
        BoxId name;
        std::uint8_t mask;
        typename PeriodicImages<Real, Dim>::Wrap wrap;
    };

    [[nodiscard]] BoxId plain_name(BoxId key) const noexcept {
        if (packed_) return key >> kIndexBits;
        return names_.empty() ? key : names_[static_cast<std::size_t>(key)];
    }

    [[nodiscard]] Side side(BoxId key) const noexcept {
        if ((key & kTranslatedKey) == 0) {
            const auto source = static_cast<std::uint32_t>(packed_ ? key & kIndexMask : key);
            return Side{source, plain_name(key), 0, {}};
        }
        const auto& record = images_.record(key);
        const BoxId name = names_.empty() ? record.source : names_[record.source];
        return Side{record.source, name, record.mask, record.wrap};
    }

    void emit(BoxId a, BoxId b, const std::array<std::int32_t, 3>& shift) {
        if (out_.size() == end_)
            throw PairLimitError("detect: more than " + std::to_string(limit_) +
                                 " overlapping pairs (max_pairs_held) in the periodic detection");
        if (b < a) std::swap(a, b);
        out_.push_back(PeriodicPair{a, b, shift});
    }

    const PeriodicImages<Real, Dim>& images_;
    std::span<const Box<Real, Dim>> boxes_;
    std::span<const BoxId> names_;
    const PeriodicDomain<Real, Dim>& domain_;
    std::vector<PeriodicPair>& out_;
    std::size_t limit_;
    std::size_t end_;
    bool packed_;
};

}  // namespace smb::detail
