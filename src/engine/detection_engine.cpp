// SPDX-License-Identifier: MIT
// The pipeline behind every front door, compiled for one box type: src/CMakeLists.txt builds
// this file once per type of instantiations.hpp (defining SMB_ENGINE_REAL and SMB_ENGINE_DIM),
// so that the four compile side by side and World and Detector share them.

#include "engine/detection_engine_detect.hpp"
#include "engine/engine_reports.hpp"

#if !defined(SMB_ENGINE_REAL) || !defined(SMB_ENGINE_DIM)
#error "detection_engine.cpp is compiled through the per-type files src/CMakeLists.txt writes"
#endif

namespace smb::detail {

template class DetectionEngine<SMB_ENGINE_REAL, SMB_ENGINE_DIM>;

// The report is the variadic tail: its template arguments hold commas.
#define SMB_INSTANTIATE_DETECT(Real, Dim, ...)                     \
    template void DetectionEngine<Real, Dim>::detect<__VA_ARGS__>( \
        const EngineInput<Real, Dim>&, const DetectionSettings&, double, __VA_ARGS__&, DetectStats&, DetectProfile&);
SMB_FOR_EACH_ENGINE_REPORT(SMB_INSTANTIATE_DETECT, SMB_ENGINE_REAL, SMB_ENGINE_DIM)
#undef SMB_INSTANTIATE_DETECT

}  // namespace smb::detail
