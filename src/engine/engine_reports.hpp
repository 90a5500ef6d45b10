// SPDX-License-Identifier: MIT
#pragma once
// The reports the front doors hand the engine, each compiled with the pipeline once per box type
// (engine/detection_engine.cpp): the caller's chunks of pairs (a World's and a Detector's own
// detections), a filtered class by packed keys or by index, and a periodic domain's images.
// A report missing here is a link error naming DetectionEngine::detect.

#include "core/pair_output.hpp"
#include "engine/detection_engine.hpp"
#include "filters/filtered_report.hpp"
#include "periodic/periodic_report.hpp"

// SMB_FOR_EACH_ENGINE_REPORT(X, Real, Dim) expands to X(Real, Dim, report type) for each.
#define SMB_FOR_EACH_ENGINE_REPORT(X, Real, Dim)                               \
    X(Real, Dim, ::smb::detail::PairOutput)                                    \
    X(Real, Dim, ::smb::detail::PackedFilterReport<::smb::detail::PairOutput>) \
    X(Real, Dim, ::smb::detail::FilteredReport<::smb::detail::PairOutput>)     \
    X(Real, Dim, ::smb::detail::PeriodicReport<Real, Dim>)
