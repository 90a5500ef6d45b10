// SPDX-License-Identifier: MIT
#pragma once
// The array a periodic detection runs the ordinary pipeline on: every box brought into the
// domain, plus images of the boxes that stick out of it (ghosts, as DEM codes call them).
//
// On each periodic axis a box is translated by a whole number of periods n (its wrap) so that
// its min lies in [lo, hi): its canonical box. Since its extent is below half the period, a
// canonical box meets another canonical box under a shift of -1, 0 or +1 periods only, and under
// +1 only if it reaches hi. So a box that reaches hi also gets an image translated by -P on that
// axis, and one for every combination of the axes where it reaches hi (up to 7 images in 3D).
// An image is named by its source and its mask u (bit k: translated by -P on axis k). A pair of
// gathered boxes (x, u) and (y, v) stands for y's shift n_x - n_y + u - v relative to x. Every
// true overlap is found as exactly one (u, v) with u & v == 0 on every axis (periodic_report.hpp
// drops the others: (1, 1) repeats (0, 0)).
//
// Rounding: translating by P rounds, so every translated box and every image is grown by a
// margin far above the rounding (kSlack epsilons of the magnitudes involved), and a box reaching
// within that margin of hi gets its images too; each pair found through them is then confirmed
// on the caller's boxes with the relation itself (overlaps_with_shift).
//
// Keys (what the pipeline carries per box and reports pairs of): a box that was not translated
// (n = 0 on every axis: the common case) is gathered exactly as it is, and its key names it
// without a memory read: its index, or, where the caller names boxes by ids below 2^32, the id
// and the index packed together. A pair of two such keys needs no decoding and no confirmation.
// A translated box or an image has kTranslatedKey set and the index of its record (source, mask,
// wrap) below it.
//
// One pass over the caller's boxes checks them (as checked_bounds does, and each extent against
// its half period), gathers them and takes the bounds of the gathered array; the common box
// costs a few comparisons and a copy.

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/invalid_box.hpp"
#include "core/scene_bounds.hpp"
#include "core/shortest_number.hpp"
#include "smb/box.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"
#include "smb/periodic.hpp"

namespace smb::detail {

/// The bit of a key that marks a box that is not its caller's box as it is (translated or an
/// image): its pairs are decoded and confirmed.
inline constexpr BoxId kTranslatedKey = BoxId{1} << 63;
/// A packed key: the id above these bits, the index in them.
inline constexpr int kIndexBits = 31;
inline constexpr BoxId kIndexMask = (BoxId{1} << kIndexBits) - 1;
/// The largest name a packed key holds: its bits end below kTranslatedKey.
inline constexpr BoxId kLargestPackedName = ~BoxId{0} >> (kIndexBits + 1);

template <std::floating_point Real, int Dim>
class PeriodicImages {
public:
    using box_type = Box<Real, Dim>;
    using Wrap = std::array<std::int32_t, Dim>;

    /// A translated box or an image: the caller's box `source`, translated by -(wrap + mask) P.
    struct Record {
        std::uint32_t source;
        std::uint8_t mask;
        Wrap wrap;
    };

    /// Gathers `boxes` (named by `names`, or by index where empty) and their images for
    /// `domain` (checked by check_domain). Throws InvalidBoxError for the first box that is
    /// invalid, too large for the domain or too far from it, having changed nothing the caller
    /// can see (its arrays are this object's scratch).
    void build(std::span<const box_type> boxes, std::span<const BoxId> names, const PeriodicDomain<Real, Dim>& domain) {
        if (boxes.size() > kIndexMask) throw ArgumentError("periodic detection: at most 2^31 - 1 boxes");
        const std::size_t n = boxes.size();
        gathered_.resize(n);
        keys_.resize(n);
        records_.clear();
        images_.clear();
        image_keys_.clear();
        const Axes axes = axes_of(domain);
        bool valid = true;
        packed_ = !names.empty();
        bool names_fit = true;
        bounds_.lo.fill(std::numeric_limits<Real>::infinity());
        bounds_.hi.fill(-std::numeric_limits<Real>::infinity());
        for (std::size_t i = 0; i < n; ++i) {
            const box_type& box = boxes[i];
            bool plain = true;
            for (int k = 0; k < Dim; ++k) {
                const auto ks = static_cast<std::size_t>(k);
                valid &= box.min[ks] <= box.max[ks];  // NaN fails it; infinities show in the bounds
                if (!axes.periodic[ks]) continue;
                valid &= 2 * (static_cast<double>(box.max[ks]) - static_cast<double>(box.min[ks])) < axes.period[ks];
                plain &=
                    box.min[ks] >= axes.lo_real[ks] && box.min[ks] < axes.hi_real[ks] && box.max[ks] < axes.reach[ks];
            }
            BoxId key = i;
            if (packed_) {
                // A name above kLargestPackedName would reach kTranslatedKey (or past it) and
                // pass for a translated box: its key is the index until packing is given up.
                if (names[i] <= kLargestPackedName) {
                    key |= names[i] << kIndexBits;
                } else {
                    names_fit = false;
                }
            }
            if (plain) [[likely]] {
                gathered_[i] = box;
                keys_[i] = key;
                widen(box);
            } else if (valid) {
                gather(static_cast<std::uint32_t>(i), box, axes, key);
            } else {
                break;  // the box is named below
            }
        }
        if (n != 0) {
            for (int k = 0; k < Dim; ++k) valid &= std::isfinite(bounds_.lo[k]) && std::isfinite(bounds_.hi[k]);
        }
        if (!valid || !far_ok_) throw_first_invalid(boxes, names, domain);
        if (packed_ && !names_fit) {
            // An id too large to pack: keys are indices, and names are read from the array.
            packed_ = false;
            for (std::size_t i = 0; i < n; ++i) {
                if ((keys_[i] & kTranslatedKey) == 0) keys_[i] = i;
            }
        }
        gathered_.insert(gathered_.end(), images_.begin(), images_.end());
        keys_.insert(keys_.end(), image_keys_.begin(), image_keys_.end());
    }

    [[nodiscard]] std::span<const box_type> gathered() const noexcept { return gathered_; }
    [[nodiscard]] std::span<const BoxId> keys() const noexcept { return keys_; }
    /// The bounds of gathered() (not empty).
    [[nodiscard]] const SceneBounds<Real, Dim>& bounds() const noexcept { return bounds_; }
    /// Whether plain keys hold the names (ids) with the index.
    [[nodiscard]] bool packed() const noexcept { return packed_; }

    /// The record of a key with kTranslatedKey.
    [[nodiscard]] const Record& record(BoxId key) const noexcept {
        return records_[static_cast<std::size_t>(key & ~kTranslatedKey)];
    }

    void clear() { *this = PeriodicImages(); }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return (gathered_.capacity() + images_.capacity()) * sizeof(box_type) +
               (keys_.capacity() + image_keys_.capacity()) * sizeof(BoxId) + records_.capacity() * sizeof(Record);
    }

private:
    /// Margins are this many epsilons of Real times the magnitudes a translation involves:
    /// far above the rounding of the translations (a few half-ulps in double) and of storing a
    /// translated coordinate as Real (half an ulp of Real).
    static constexpr double kSlack = 16 * static_cast<double>(std::numeric_limits<Real>::epsilon());

    struct Axes {
        std::array<bool, Dim> periodic{};
        std::array<double, Dim> lo{};
        std::array<double, Dim> hi{};
        std::array<double, Dim> period{};
        std::array<double, Dim> magnitude{};  // |lo| + |hi|
        std::array<Real, Dim> lo_real{};
        std::array<Real, Dim> hi_real{};
        /// A box whose min lies in [lo, hi) and whose max is below this has no image: hi less a
        /// margin at least as large as any such box's own (its coordinates are below
        /// max(|lo|, |hi|) + P in magnitude), rounded down.
        std::array<Real, Dim> reach{};
    };

    static Axes axes_of(const PeriodicDomain<Real, Dim>& domain) {
        Axes axes;
        for (int k = 0; k < Dim; ++k) {
            const auto ks = static_cast<std::size_t>(k);
            if (!domain.periodic[ks]) continue;
            axes.periodic[ks] = true;
            axes.lo[ks] = static_cast<double>(domain.lo[ks]);
            axes.hi[ks] = static_cast<double>(domain.hi[ks]);
            axes.period[ks] = domain.period(k);
            axes.magnitude[ks] = std::abs(axes.lo[ks]) + std::abs(axes.hi[ks]);
            axes.lo_real[ks] = domain.lo[ks];
            axes.hi_real[ks] = domain.hi[ks];
            const double largest = std::max(std::abs(axes.lo[ks]), std::abs(axes.hi[ks])) + axes.period[ks];
            const double reach = axes.hi[ks] - 2 * kSlack * (axes.magnitude[ks] + 2 * largest);
            Real rounded = static_cast<Real>(reach);
            if (static_cast<double>(rounded) > reach)
                rounded = std::nextafter(rounded, -std::numeric_limits<Real>::infinity());
            axes.reach[ks] = rounded;
        }
        return axes;
    }

    /// The wrap n of a min coordinate: min - n P lies in [lo, hi).
    static std::int32_t wrap_of(double min, double lo, double hi, double period) noexcept {
        double n = std::floor((min - lo) / period);
        // The division rounds: step to the period where min - n P, as computed, lies in [lo, hi).
        for (int step = 0; step < 4 && min - n * period < lo; ++step) n -= 1;
        for (int step = 0; step < 4 && min - n * period >= hi; ++step) n += 1;
        return static_cast<std::int32_t>(n);
    }

    void widen(const box_type& box) noexcept {
        for (int k = 0; k < Dim; ++k) {
            bounds_.lo[k] = std::min(bounds_.lo[k], box.min[k]);
            bounds_.hi[k] = std::max(bounds_.hi[k], box.max[k]);
        }
    }

    /// A box that is translated or reaches hi (valid so far).
    void gather(std::uint32_t i, const box_type& box, const Axes& axes, BoxId plain_key) {
        Wrap wrap{};
        std::array<double, Dim> lo{};
        std::array<double, Dim> hi{};
        std::array<double, Dim> margin{};
        bool translated = false;
        unsigned reaching = 0;  // axes where the canonical box reaches hi (within the margin)
        for (int k = 0; k < Dim; ++k) {
            const auto ks = static_cast<std::size_t>(k);
            lo[ks] = static_cast<double>(box.min[ks]);
            hi[ks] = static_cast<double>(box.max[ks]);
            if (!axes.periodic[ks]) continue;
            margin[ks] = kSlack * (axes.magnitude[ks] + std::abs(lo[ks]) + std::abs(hi[ks]));
            if (!(lo[ks] >= axes.lo[ks] && lo[ks] < axes.hi[ks])) {
                if (!(std::abs((lo[ks] - axes.lo[ks]) / axes.period[ks]) <
                      PeriodicDomain<Real, Dim>::kMaxPeriodsAway)) {
                    far_ok_ = false;  // named by throw_first_invalid
                    return;
                }
                wrap[ks] = wrap_of(lo[ks], axes.lo[ks], axes.hi[ks], axes.period[ks]);
                const double shift = static_cast<double>(wrap[ks]) * axes.period[ks];
                lo[ks] -= shift;
                hi[ks] -= shift;
                translated = true;
            }
            if (hi[ks] >= axes.hi[ks] - margin[ks]) reaching |= 1u << k;
        }
        if (translated) {
            gathered_[i] = grown(lo, hi, margin, 0, axes);
            keys_[i] = kTranslatedKey | records_.size();
            records_.push_back(Record{i, 0, wrap});
        } else {
            gathered_[i] = box;
            keys_[i] = plain_key;
        }
        widen(gathered_[i]);
        // Every non-empty subset of the reaching axes.
        for (unsigned mask = reaching; mask != 0; mask = (mask - 1) & reaching) {
            images_.push_back(grown(lo, hi, margin, mask, axes));
            widen(images_.back());
            image_keys_.push_back(kTranslatedKey | records_.size());
            records_.push_back(Record{i, static_cast<std::uint8_t>(mask), wrap});
        }
    }

    /// The canonical box [lo, hi] translated by -P on the axes of `mask`, grown by the margins
    /// (periodic axes only; the others are exact).
    static box_type grown(const std::array<double, Dim>& lo, const std::array<double, Dim>& hi,
                          const std::array<double, Dim>& margin, unsigned mask, const Axes& axes) {
        box_type out;
        for (int k = 0; k < Dim; ++k) {
            const auto ks = static_cast<std::size_t>(k);
            const double shift = (mask >> k) & 1u ? axes.period[ks] : 0.0;
            out.min[ks] = static_cast<Real>(lo[ks] - shift - margin[ks]);
            out.max[ks] = static_cast<Real>(hi[ks] - shift + margin[ks]);
        }
        return out;
    }

    /// Throws InvalidBoxError for the first box that is invalid, too large for the domain or
    /// too far from it (one was found).
    [[noreturn]] void throw_first_invalid(std::span<const box_type> boxes, std::span<const BoxId> names,
                                          const PeriodicDomain<Real, Dim>& domain) {
        far_ok_ = true;
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            const box_type& box = boxes[i];
            const BoxId name = names.empty() ? static_cast<BoxId>(i) : names[i];
            if (!is_valid(box)) throw InvalidBoxError(describe_invalid_box(name, box));
            for (int k = 0; k < Dim; ++k) {
                const auto ks = static_cast<std::size_t>(k);
                if (!domain.periodic[ks]) continue;
                const double period = domain.period(k);
                const double extent = static_cast<double>(box.max[ks]) - static_cast<double>(box.min[ks]);
                const std::string axis(1, "xyz"[k]);
                if (!(2 * extent < period))
                    throw InvalidBoxError("box " + std::to_string(name) +
                                          " is too large for the periodic domain: its " + axis + " extent " +
                                          shortest_number(extent) + " is not below half the period " +
                                          shortest_number(period));
                const double away = (static_cast<double>(box.min[ks]) - static_cast<double>(domain.lo[ks])) / period;
                if (!(std::abs(away) < PeriodicDomain<Real, Dim>::kMaxPeriodsAway))
                    throw InvalidBoxError("box " + std::to_string(name) + " lies more than 2^20 periods from the " +
                                          axis + " interval of the periodic domain");
            }
        }
        throw InvalidBoxError("periodic detection: an invalid box");  // not reached
    }

    std::vector<box_type> gathered_;  // the caller's boxes (canonical), then the images
    std::vector<BoxId> keys_;         // per gathered box
    std::vector<Record> records_;     // translated boxes and images
    std::vector<box_type> images_;    // built apart, then appended
    std::vector<BoxId> image_keys_;
    SceneBounds<Real, Dim> bounds_;
    bool packed_ = false;
    bool far_ok_ = true;
};

}  // namespace smb::detail
