// SPDX-License-Identifier: MIT
#include "axial_regions.hpp"

#include <algorithm>
#include <functional>
#include <limits>

namespace smb::mpi::detail {

template <int Dim>
std::array<int, Dim> regions_per_axis_for(int ranks) {
    std::vector<int> factors;
    for (int f = 2; static_cast<long long>(f) * f <= ranks; ++f) {
        while (ranks % f == 0) {
            factors.push_back(f);
            ranks /= f;
        }
    }
    if (ranks > 1) factors.push_back(ranks);
    std::sort(factors.begin(), factors.end(), std::greater<>());
    std::array<int, Dim> per_axis{};
    per_axis.fill(1);
    for (int factor : factors) *std::min_element(per_axis.begin(), per_axis.end()) *= factor;
    return per_axis;
}

template <std::floating_point Real, int Dim>
AxialRegions<Real, Dim>::AxialRegions(int ranks) : per_axis_(regions_per_axis_for<Dim>(ranks)) {
    int groups = 1;
    for (int k = 0; k < Dim; ++k) {
        groups_[k] = groups;
        cuts_[k].assign(static_cast<std::size_t>(groups) * static_cast<std::size_t>(per_axis_[k] - 1), Real(0));
        groups *= per_axis_[k];
    }
    has_cuts_ = ranks == 1;
}

template <std::floating_point Real, int Dim>
void AxialRegions<Real, Dim>::recut(MPI_Comm comm, std::span<const box_type> boxes) {
    const std::size_t n = boxes.size();
    std::vector<int> group_of(n, 0);
    std::vector<Real> values(n);
    for (int axis = 0; axis < Dim; ++axis) {
        const int slabs = per_axis_[axis];
        const int groups = groups_[axis];
        const int cuts_per_group = slabs - 1;
        if (cuts_per_group == 0) continue;  // one slab: every box keeps its group
        // This rank's centres on this axis, bucketed by group and sorted within each bucket, so
        // that the count below a plane is a binary search.
        std::vector<std::size_t> offsets(static_cast<std::size_t>(groups) + 1, 0);
        for (std::size_t i = 0; i < n; ++i) ++offsets[static_cast<std::size_t>(group_of[i]) + 1];
        for (int g = 0; g < groups; ++g) offsets[g + 1] += offsets[g];
        std::vector<std::size_t> fill(offsets.begin(), offsets.end() - 1);
        for (std::size_t i = 0; i < n; ++i) values[fill[group_of[i]]++] = centre_of(boxes[i])[axis];
        // Each group's total, smallest and largest centre over all ranks, in two reductions.
        std::vector<unsigned long long> totals(static_cast<std::size_t>(groups));
        std::vector<double> extremes(2 * static_cast<std::size_t>(groups), std::numeric_limits<double>::infinity());
        for (int g = 0; g < groups; ++g) {
            const auto first = values.begin() + static_cast<std::ptrdiff_t>(offsets[g]);
            const auto last = values.begin() + static_cast<std::ptrdiff_t>(offsets[g + 1]);
            std::sort(first, last);
            totals[g] = offsets[g + 1] - offsets[g];
            if (first != last) {
                extremes[2 * g] = static_cast<double>(*first);
                extremes[2 * g + 1] = -static_cast<double>(*(last - 1));
            }
        }
        MPI_Allreduce(MPI_IN_PLACE, totals.data(), groups, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
        MPI_Allreduce(MPI_IN_PLACE, extremes.data(), 2 * groups, MPI_DOUBLE, MPI_MIN, comm);

        const std::size_t cut_count = static_cast<std::size_t>(groups) * static_cast<std::size_t>(cuts_per_group);
        // The cut planes, each bisected between the smallest and largest centre of its group
        // until the count of centres below it reaches its share (or the interval cannot shrink).
        std::vector<Real> lower(cut_count), upper(cut_count);
        std::vector<unsigned long long> target(cut_count);
        std::vector<char> done(cut_count, 0);
        for (int g = 0; g < groups; ++g) {
            for (int j = 0; j < cuts_per_group; ++j) {
                const std::size_t c = static_cast<std::size_t>(g) * static_cast<std::size_t>(cuts_per_group) + j;
                target[c] = totals[g] * static_cast<unsigned long long>(j + 1) / static_cast<unsigned long long>(slabs);
                if (totals[g] == 0) {  // an empty group: any plane will do
                    lower[c] = upper[c] = Real(0);
                    done[c] = 1;
                } else {
                    lower[c] = static_cast<Real>(extremes[2 * g]);
                    upper[c] = static_cast<Real>(-extremes[2 * g + 1]);
                }
            }
        }
        // Every rank runs the same iterations on the same reduced counts, so all agree on when
        // to stop. 64 rounds settle any float and any double within a factor 2^-64 of the
        // group's span; the balance needs no more.
        std::vector<unsigned long long> below(cut_count);
        std::vector<Real> middle(cut_count);
        for (int round = 0; round < 64; ++round) {
            bool any_active = false;
            for (std::size_t c = 0; c < cut_count; ++c) {
                middle[c] = lower[c] * Real(0.5) + upper[c] * Real(0.5);
                if (!done[c] && !(lower[c] < middle[c] && middle[c] < upper[c])) done[c] = 1;
                any_active = any_active || !done[c];
                const std::size_t g = c / static_cast<std::size_t>(cuts_per_group);
                const auto first = values.begin() + static_cast<std::ptrdiff_t>(offsets[g]);
                const auto last = values.begin() + static_cast<std::ptrdiff_t>(offsets[g + 1]);
                below[c] =
                    done[c] ? 0 : static_cast<unsigned long long>(std::lower_bound(first, last, middle[c]) - first);
            }
            if (!any_active) break;
            MPI_Allreduce(MPI_IN_PLACE, below.data(), static_cast<int>(cut_count), MPI_UNSIGNED_LONG_LONG, MPI_SUM,
                          comm);
            for (std::size_t c = 0; c < cut_count; ++c) {
                if (done[c]) continue;
                if (below[c] >= target[c]) {
                    upper[c] = middle[c];
                    if (below[c] == target[c]) done[c] = 1;
                } else {
                    lower[c] = middle[c];
                }
            }
        }
        // Ascending within each group, whatever ties did to the bisections.
        for (std::size_t c = 0; c < cut_count; ++c) {
            const bool first_of_group = c % static_cast<std::size_t>(cuts_per_group) == 0;
            cuts_[axis][c] = first_of_group ? upper[c] : std::max(upper[c], cuts_[axis][c - 1]);
        }
        for (std::size_t i = 0; i < n; ++i) {
            const Real* planes = cuts_of(axis, group_of[i]);
            const Real value = centre_of(boxes[i])[axis];
            const int slab = static_cast<int>(std::upper_bound(planes, planes + cuts_per_group, value) - planes);
            group_of[i] = group_of[i] * slabs + slab;
        }
    }
    has_cuts_ = true;
}

template <std::floating_point Real, int Dim>
int AxialRegions<Real, Dim>::region_of(const std::array<Real, Dim>& point) const noexcept {
    int group = 0;
    for (int axis = 0; axis < Dim; ++axis) {
        const int cuts_per_group = per_axis_[axis] - 1;
        const Real* planes = cuts_of(axis, group);
        const int slab = static_cast<int>(std::upper_bound(planes, planes + cuts_per_group, point[axis]) - planes);
        group = group * per_axis_[axis] + slab;
    }
    return group;
}

template <std::floating_point Real, int Dim>
void AxialRegions<Real, Dim>::regions_of(const box_type& box, std::vector<int>& out) const {
    regions_of_from(box, 0, 0, out);
}

template <std::floating_point Real, int Dim>
void AxialRegions<Real, Dim>::regions_of_from(const box_type& box, int axis, int group, std::vector<int>& out) const {
    const int slabs = per_axis_[axis];
    const Real* planes = cuts_of(axis, group);
    // The first slab whose upper plane lies above box.min: planes at or below box.min end
    // slabs the box does not enter (a slab's upper face is open).
    int slab = static_cast<int>(std::upper_bound(planes, planes + (slabs - 1), box.min[axis]) - planes);
    for (; slab < slabs; ++slab) {
        if (slab > 0 && planes[slab - 1] > box.max[axis]) break;  // the slab starts above the box
        const int next = group * slabs + slab;
        if (axis + 1 == Dim) {
            out.push_back(next);
        } else {
            regions_of_from(box, axis + 1, next, out);
        }
    }
}

template <std::floating_point Real, int Dim>
Box<double, Dim> AxialRegions<Real, Dim>::bounds(int region) const {
    std::array<int, Dim> slab{};
    for (int axis = Dim - 1; axis >= 0; --axis) {
        slab[axis] = region % per_axis_[axis];
        region /= per_axis_[axis];
    }
    Box<double, Dim> extent;
    int group = 0;
    for (int axis = 0; axis < Dim; ++axis) {
        const Real* planes = cuts_of(axis, group);
        const int s = slab[axis];
        extent.min[axis] = s == 0 ? -std::numeric_limits<double>::infinity() : static_cast<double>(planes[s - 1]);
        extent.max[axis] =
            s == per_axis_[axis] - 1 ? std::numeric_limits<double>::infinity() : static_cast<double>(planes[s]);
        group = group * per_axis_[axis] + s;
    }
    return extent;
}

template std::array<int, 2> regions_per_axis_for<2>(int);
template std::array<int, 3> regions_per_axis_for<3>(int);
template class AxialRegions<float, 2>;
template class AxialRegions<float, 3>;
template class AxialRegions<double, 2>;
template class AxialRegions<double, 3>;

}  // namespace smb::mpi::detail
