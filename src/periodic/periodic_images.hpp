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
// An image is named by its owner and its mask u (bit k: translated by -P on axis k). A pair of
// gathered boxes (x, u) and (y, v) stands for y's shift n_x - n_y + u - v relative to x. Every
// true overlap is found as exactly one (u, v) with u & v == 0 on every axis (periodic_report.hpp
// drops the others: (1, 1) repeats (0, 0)).
//
// Rounding: translating by P rounds, so every translated box and every image is grown by a
// margin far above the rounding (kSlack epsilons of the magnitudes involved), and a box reaching
// within that margin of hi gets its images too; each pair found through them is then confirmed
// on the caller's boxes with the relation itself (overlaps_with_shift). A box that was not
// translated (n = 0 on every axis: the common case) is gathered exactly as it is, so that a pair
// of two such boxes needs no confirmation and reads no memory (its key is its index).

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
#include "core/shortest_number.hpp"
#include "smb/box.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"
#include "smb/periodic.hpp"

namespace smb::detail {

/// The bit of a key that marks a box that is not its caller's box as it is (translated or an
/// image): its pairs are decoded and confirmed. Below it, a key is the box's index.
inline constexpr BoxId kTranslatedKey = BoxId{1} << 63;

template <std::floating_point Real, int Dim>
class PeriodicImages {
public:
    using box_type = Box<Real, Dim>;
    using Wrap = std::array<std::int32_t, Dim>;

    /// What a gathered key stands for: the caller's box `owner`, translated by `mask`.
    struct Decoded {
        std::uint32_t owner;
        std::uint8_t mask;
    };

    /// Throws InvalidBoxError for the first box i with alive(i) that is invalid, too large for
    /// the domain, or too far from it, naming it as name(i). Changes nothing.
    template <class Alive, class Name>
    static void check(std::span<const box_type> boxes, const PeriodicDomain<Real, Dim>& domain, Alive&& alive,
                      Name&& name) {
        if (boxes.size() >= (std::size_t{1} << 31))
            throw ArgumentError("periodic detection: at most 2^31 - 1 boxes");
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            if (!alive(i)) continue;
            const box_type& box = boxes[i];
            if (!is_valid(box)) throw InvalidBoxError(describe_invalid_box(name(i), box));
            for (int k = 0; k < Dim; ++k) {
                const auto ks = static_cast<std::size_t>(k);
                if (!domain.periodic[ks]) continue;
                const double period = domain.period(k);
                const double extent = static_cast<double>(box.max[ks]) - static_cast<double>(box.min[ks]);
                const std::string axis(1, "xyz"[k]);
                if (!(2 * extent < period))
                    throw InvalidBoxError("box " + std::to_string(name(i)) + " is too large for the periodic domain: its " +
                                          axis + " extent " + shortest_number(extent) + " is not below half the period " +
                                          shortest_number(period));
                const double away = (static_cast<double>(box.min[ks]) - static_cast<double>(domain.lo[ks])) / period;
                if (!(std::abs(away) < PeriodicDomain<Real, Dim>::kMaxPeriodsAway))
                    throw InvalidBoxError("box " + std::to_string(name(i)) + " lies more than 2^20 periods from the " +
                                          axis + " interval of the periodic domain");
            }
        }
    }

    /// Gathers `boxes` (checked by check()) and their images for `domain`.
    void build(std::span<const box_type> boxes, const PeriodicDomain<Real, Dim>& domain) {
        n_ = boxes.size();
        gathered_.resize(n_);
        keys_.resize(n_);
        wraps_.resize(n_);
        owner_.clear();
        mask_.clear();
        images_.clear();
        std::array<Axis, Dim> axes{};
        for (int k = 0; k < Dim; ++k) {
            const auto ks = static_cast<std::size_t>(k);
            axes[ks] = Axis{domain.periodic[ks], static_cast<double>(domain.lo[ks]), static_cast<double>(domain.hi[ks]),
                            domain.period(k), std::abs(static_cast<double>(domain.lo[ks])) +
                                                  std::abs(static_cast<double>(domain.hi[ks]))};
        }
        for (std::size_t i = 0; i < n_; ++i) gather(static_cast<std::uint32_t>(i), boxes[i], axes);
        gathered_.insert(gathered_.end(), images_.begin(), images_.end());
        for (std::size_t j = 0; j < images_.size(); ++j) keys_.push_back(kTranslatedKey | (n_ + j));
    }

    [[nodiscard]] std::span<const box_type> gathered() const noexcept { return gathered_; }
    [[nodiscard]] std::span<const BoxId> keys() const noexcept { return keys_; }
    /// The caller's boxes (the first entries of gathered()).
    [[nodiscard]] std::size_t boxes() const noexcept { return n_; }
    [[nodiscard]] std::size_t images() const noexcept { return owner_.size(); }

    [[nodiscard]] Decoded decode(BoxId key) const noexcept {
        const std::size_t index = key & ~kTranslatedKey;
        if (index < n_) return Decoded{static_cast<std::uint32_t>(index), 0};
        return Decoded{owner_[index - n_], mask_[index - n_]};
    }
    /// The periods box `owner` was translated by (n: its canonical box is box - n P).
    [[nodiscard]] const Wrap& wrap(std::uint32_t owner) const noexcept { return wraps_[owner]; }

    void clear() { *this = PeriodicImages(); }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return gathered_.capacity() * sizeof(box_type) + keys_.capacity() * sizeof(BoxId) +
               wraps_.capacity() * sizeof(Wrap) + owner_.capacity() * sizeof(std::uint32_t) + mask_.capacity() +
               images_.capacity() * sizeof(box_type);
    }

private:
    /// Margins are this many epsilons of Real times the magnitudes a translation involves:
    /// far above the rounding of the translations (a few half-ulps in double) and of storing a
    /// translated coordinate as Real (half an ulp of Real).
    static constexpr double kSlack = 16 * static_cast<double>(std::numeric_limits<Real>::epsilon());

    struct Axis {
        bool periodic;
        double lo;
        double hi;
        double period;
        double magnitude;  // |lo| + |hi|
    };

    /// The wrap n of a min coordinate: min - n P lies in [lo, hi).
    static std::int32_t wrap_of(double min, const Axis& axis) noexcept {
        double n = std::floor((min - axis.lo) / axis.period);
        // The division rounds: step to the period where min - n P, as computed, lies in [lo, hi).
        for (int step = 0; step < 4 && min - n * axis.period < axis.lo; ++step) n -= 1;
        for (int step = 0; step < 4 && min - n * axis.period >= axis.hi; ++step) n += 1;
        return static_cast<std::int32_t>(n);
    }

    void gather(std::uint32_t i, const box_type& box, const std::array<Axis, Dim>& axes) {
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
            const Axis& axis = axes[ks];
            if (!axis.periodic) continue;
            margin[ks] = kSlack * (axis.magnitude + std::abs(lo[ks]) + std::abs(hi[ks]));
            if (!(lo[ks] >= axis.lo && lo[ks] < axis.hi)) {
                wrap[ks] = wrap_of(lo[ks], axis);
                const double shift = static_cast<double>(wrap[ks]) * axis.period;
                lo[ks] -= shift;
                hi[ks] -= shift;
                translated = true;
            }
            if (hi[ks] >= axis.hi - margin[ks]) reaching |= 1u << k;
        }
        wraps_[i] = wrap;
        if (translated) {
            gathered_[i] = grown(lo, hi, margin, 0, axes);
            keys_[i] = kTranslatedKey | i;
        } else {
            gathered_[i] = box;
            keys_[i] = i;
        }
        // Every non-empty subset of the reaching axes.
        for (unsigned mask = reaching; mask != 0; mask = (mask - 1) & reaching) {
            images_.push_back(grown(lo, hi, margin, mask, axes));
            owner_.push_back(i);
            mask_.push_back(static_cast<std::uint8_t>(mask));
        }
    }

    /// The canonical box [lo, hi] translated by -P on the axes of `mask`, grown by the margins
    /// (periodic axes only; the others are exact).
    static box_type grown(const std::array<double, Dim>& lo, const std::array<double, Dim>& hi,
                          const std::array<double, Dim>& margin, unsigned mask, const std::array<Axis, Dim>& axes) {
        box_type out;
        for (int k = 0; k < Dim; ++k) {
            const auto ks = static_cast<std::size_t>(k);
            const double shift = (mask >> k) & 1u ? axes[ks].period : 0.0;
            out.min[ks] = static_cast<Real>(lo[ks] - shift - margin[ks]);
            out.max[ks] = static_cast<Real>(hi[ks] - shift + margin[ks]);
        }
        return out;
    }

    std::size_t n_ = 0;
    std::vector<box_type> gathered_;  // the caller's boxes (canonical), then the images
    std::vector<BoxId> keys_;         // per gathered box
    std::vector<Wrap> wraps_;         // per caller's box
    std::vector<std::uint32_t> owner_;
    std::vector<std::uint8_t> mask_;
    std::vector<box_type> images_;  // built apart, then appended
};

}  // namespace smb::detail
