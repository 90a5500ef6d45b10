// SPDX-License-Identifier: MIT
#pragma once
// The report the pipeline calls with the pairs of gathered boxes it finds in a periodic
// detection (periodic_images.hpp): it turns each into a pair of the caller's boxes and their
// shift, or drops it.
//
// Two boxes gathered as they are (keys without kTranslatedKey) overlap exactly as the caller's
// boxes do, under the shift 0: reported at once, without reading memory. Any other pair is
// decoded to (owner, mask) on both sides: the same owner (a box and its own image, which never
// overlap in truth) and masks that share an axis (a repeat of a pair found without both images)
// are dropped; the rest are confirmed on the caller's boxes with overlaps_with_shift, since
// the gathered boxes were grown to cover the rounding of their translation.

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
    using box_type = Box<Real, Dim>;

    /// `names`: the name of each of the caller's boxes (a World's ids), or empty for its index.
    /// The pairs are appended to `out`, at most `limit` of them (else PairLimitError).
    PeriodicReport(const PeriodicImages<Real, Dim>& images, std::span<const box_type> boxes,
                   std::span<const BoxId> names, const PeriodicDomain<Real, Dim>& domain,
                   std::vector<PeriodicPair>& out, std::size_t limit)
        : images_(images), boxes_(boxes), names_(names), domain_(domain), out_(out), limit_(limit), end_(out.size() + limit) {}

    void operator()(BoxId x, BoxId y) {
        if (((x | y) & kTranslatedKey) == 0) [[likely]] {
            emit(name(x), name(y), {});
            return;
        }
        const auto dx = images_.decode(x);
        const auto dy = images_.decode(y);
        if (dx.owner == dy.owner || (dx.mask & dy.mask) != 0) return;
        // y's shift relative to x: n_x - n_y + u - v on every periodic axis.
        const auto& nx = images_.wrap(dx.owner);
        const auto& ny = images_.wrap(dy.owner);
        std::array<std::int32_t, 3> shift{};
        for (int k = 0; k < Dim; ++k) {
            const auto ks = static_cast<std::size_t>(k);
            shift[ks] = nx[ks] - ny[ks] + static_cast<std::int32_t>((dx.mask >> k) & 1u) -
                        static_cast<std::int32_t>((dy.mask >> k) & 1u);
        }
        BoxId a = name(dx.owner);
        BoxId b = name(dy.owner);
        std::uint32_t first = dx.owner;
        std::uint32_t second = dy.owner;
        if (b < a) {
            std::swap(a, b);
            std::swap(first, second);
            for (auto& s : shift) s = -s;
        }
        if (!overlaps_with_shift(boxes_[first], boxes_[second], shift, domain_)) return;
        emit(a, b, shift);
    }

    void append(std::span<const Pair> pairs) {
        for (const Pair& p : pairs) (*this)(p.a, p.b);
    }

private:
    [[nodiscard]] BoxId name(BoxId index) const noexcept {
        return names_.empty() ? index : names_[static_cast<std::size_t>(index)];
    }

    void emit(BoxId a, BoxId b, const std::array<std::int32_t, 3>& shift) {
        if (out_.size() == end_)
            throw PairLimitError("detect: more than " + std::to_string(limit_) +
                                 " overlapping pairs (max_pairs_held) in the periodic detection");
        if (b < a) std::swap(a, b);
        out_.push_back(PeriodicPair{a, b, shift});
    }

    const PeriodicImages<Real, Dim>& images_;
    std::span<const box_type> boxes_;
    std::span<const BoxId> names_;
    const PeriodicDomain<Real, Dim>& domain_;
    std::vector<PeriodicPair>& out_;
    std::size_t limit_;
    std::size_t end_;
};

}  // namespace smb::detail
