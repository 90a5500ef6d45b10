// SPDX-License-Identifier: MIT
#pragma once
// Compares the pairs a detection reported with the expected ones and, when they differ, says
// exactly how: pairs out of order (a >= b), duplicates, missing and extra pairs, each shown
// with the boxes involved so that a failure can be reproduced by hand.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::test {

/// Shows a box as [min, max] with enough digits to rebuild it exactly.
template <std::floating_point Real, int Dim>
std::string describe(const Box<Real, Dim>& box) {
    std::ostringstream out;
    out.precision(std::numeric_limits<Real>::max_digits10);
    out << '[';
    for (int k = 0; k < Dim; ++k) out << (k ? ", " : "(") << box.min[k];
    out << ") .. ";
    for (int k = 0; k < Dim; ++k) out << (k ? ", " : "(") << box.max[k];
    out << ")]";
    return out.str();
}

/// Describes the box stored under an id (or says it is unknown); used in failure messages.
using BoxDescriber = std::function<std::string(BoxId)>;

namespace detail {

inline void show_pairs(std::ostringstream& out, const char* heading, const std::vector<Pair>& pairs,
                       const BoxDescriber& describe_box) {
    constexpr std::size_t shown = 10;
    if (pairs.empty()) return;
    out << "\n  " << heading << " (" << pairs.size() << "):";
    for (std::size_t i = 0; i < std::min(shown, pairs.size()); ++i) {
        const Pair& p = pairs[i];
        out << "\n    (" << p.a << ", " << p.b << ")";
        if (describe_box) out << "  " << describe_box(p.a) << "  " << describe_box(p.b);
    }
    if (pairs.size() > shown) out << "\n    ...";
}

}  // namespace detail

/// Success when `reported` holds exactly the pairs of `expected` (sorted, a < b), each once,
/// with a < b, in any order.
inline ::testing::AssertionResult same_pairs(std::vector<Pair> reported, const std::vector<Pair>& expected,
                                             const BoxDescriber& describe_box = {}) {
    std::vector<Pair> misordered;
    for (const Pair& p : reported) {
        if (!(p.a < p.b)) misordered.push_back(p);
    }
    std::sort(reported.begin(), reported.end());
    std::vector<Pair> duplicates;
    for (std::size_t i = 1; i < reported.size(); ++i) {
        if (reported[i] == reported[i - 1]) duplicates.push_back(reported[i]);
    }
    const auto unique_end = std::unique(reported.begin(), reported.end());
    std::vector<Pair> missing;
    std::vector<Pair> extra;
    std::set_difference(expected.begin(), expected.end(), reported.begin(), unique_end, std::back_inserter(missing));
    std::set_difference(reported.begin(), unique_end, expected.begin(), expected.end(), std::back_inserter(extra));
    if (misordered.empty() && duplicates.empty() && missing.empty() && extra.empty())
        return ::testing::AssertionSuccess();

    std::ostringstream out;
    out << "reported " << (unique_end - reported.begin()) << " distinct pairs, expected " << expected.size();
    detail::show_pairs(out, "pairs with a >= b", misordered, describe_box);
    detail::show_pairs(out, "duplicated pairs", duplicates, describe_box);
    detail::show_pairs(out, "missing pairs", missing, describe_box);
    detail::show_pairs(out, "extra pairs", extra, describe_box);
    return ::testing::AssertionFailure() << out.str();
}

}  // namespace smb::test
