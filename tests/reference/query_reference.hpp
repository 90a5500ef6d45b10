// SPDX-License-Identifier: MIT
#pragma once
// Brute-force answers to box queries and ray casts, and the checks that compare an index with
// them: the tests of smb::BoxIndex and of World's queries.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "smb/box.hpp"
#include "smb/box_index.hpp"
#include "smb/query.hpp"

namespace smb::test {

template <class Real, int Dim>
std::vector<BoxId> brute_query(std::span<const BoxId> ids, std::span<const Box<Real, Dim>> boxes,
                               const Box<Real, Dim>& q) {
    std::vector<BoxId> out;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (overlaps(q, boxes[i])) out.push_back(ids[i]);
    }
    std::sort(out.begin(), out.end());
    return out;
}

/// Every hit sorted by (t, id): the answer of RayHits::all; its first is RayHits::nearest.
template <class Real, int Dim>
std::vector<RayHit<Real>> brute_cast(std::span<const BoxId> ids, std::span<const Box<Real, Dim>> boxes,
                                     const Ray<Real, Dim>& ray) {
    struct Exact {
        double t;
        BoxId id;
    };
    std::vector<Exact> hits;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        // Sorted by the t reported, rounded to Real.
        if (const auto t = ray_entry(ray, boxes[i]))
            hits.push_back({static_cast<double>(static_cast<Real>(*t)), ids[i]});
    }
    std::sort(hits.begin(), hits.end(),
              [](const Exact& a, const Exact& b) { return a.t != b.t ? a.t < b.t : a.id < b.id; });
    std::vector<RayHit<Real>> out;
    for (const Exact& h : hits) out.push_back({h.id, static_cast<Real>(h.t)});
    return out;
}

template <class Real, int Dim>
std::string describe(const Ray<Real, Dim>& ray) {
    // Appends piece by piece: GCC 12 warns falsely (-Wrestrict) on " " + std::string.
    std::string s = "ray origin";
    auto add = [&](double v) {
        s.push_back(' ');
        s.append(std::to_string(v));
    };
    for (int k = 0; k < Dim; ++k) add(ray.origin[k]);
    s.append(" direction");
    for (int k = 0; k < Dim; ++k) add(ray.direction[k]);
    s.append(" max_t");
    add(ray.max_t);
    return s;
}

/// Queries `index` (or anything with the same query and cast_ray) and compares with brute force.
template <class Index, class Real, int Dim>
void expect_query(Index& index, std::span<const BoxId> ids, std::span<const Box<Real, Dim>> boxes,
                  const Box<Real, Dim>& q) {
    std::vector<BoxId> got;
    index.query(q, got);
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, brute_query(ids, boxes, q));
}

template <class Index, class Real, int Dim>
void expect_cast(Index& index, std::span<const BoxId> ids, std::span<const Box<Real, Dim>> boxes,
                 const Ray<Real, Dim>& ray) {
    const std::vector<RayHit<Real>> want = brute_cast(ids, boxes, ray);
    std::vector<RayHit<Real>> got;
    index.cast_ray(ray, RayHits::all, got);
    ASSERT_EQ(got.size(), want.size()) << describe(ray);
    for (std::size_t i = 0; i < got.size(); ++i) {
        ASSERT_EQ(got[i].id, want[i].id) << describe(ray) << " hit " << i;
        ASSERT_EQ(got[i].t, want[i].t) << describe(ray) << " hit " << i;
    }
    index.cast_ray(ray, RayHits::nearest, got);
    if (want.empty()) {
        ASSERT_TRUE(got.empty()) << describe(ray);
    } else {
        ASSERT_EQ(got.size(), 1U) << describe(ray);
        ASSERT_EQ(got[0].id, want[0].id) << describe(ray);
        ASSERT_EQ(got[0].t, want[0].t) << describe(ray);
    }
}

}  // namespace smb::test
