// SPDX-License-Identifier: MIT
#pragma once
// What the Detector's periodic tests share (test_periodic_detector.cpp and
// test_periodic_detector_edges.cpp): their fixture, typed over the four shapes, and the brute
// force over boxes named by their index.

#include <gtest/gtest.h>

#include <concepts>
#include <vector>

#include "reference/detector_shapes.hpp"
#include "reference/periodic_brute_force.hpp"
#include "smb/periodic.hpp"

namespace smb::test {

template <class Shape>
class PeriodicDetectorTest : public ::testing::Test {};

template <std::floating_point Real, int Dim>
std::vector<PeriodicPair> brute(const std::vector<Box<Real, Dim>>& boxes, const PeriodicDomain<Real, Dim>& domain) {
    return brute_force_periodic_pairs<Real, Dim>(boxes, {}, domain);
}

}  // namespace smb::test
