// SPDX-License-Identifier: MIT
#include "core/pair_output.hpp"

#include <functional>

namespace smb::detail {

const PairAppender* appender_behind(const PairSink& sink) noexcept {
    const auto* held = sink.target<std::reference_wrapper<const PairAppender>>();
    return held != nullptr ? &held->get() : nullptr;
}

}  // namespace smb::detail
