// SPDX-License-Identifier: MIT
#pragma once
// Whether the skin list pays for itself. A life: the detections the candidates served between two
// rebuilds. A rebuild costs more than a detection without a skin, so two short lives running
// (the motion outruns the skin) and the skin list steps aside.

#include <cstddef>

#include "core/tuning.hpp"

namespace smb::detail {

class CandidateLives {
public:
    /// Counts a detection that rebuilt the candidates, or kept them; true at the end of the second
    /// short life running.
    [[nodiscard]] bool short_again(bool rebuilt) noexcept {
        if (!rebuilt) {
            ++kept_since_rebuild_;
            return false;
        }
        if (kept_since_rebuild_ >= tuning::short_skin_life) {
            short_lives_ = 0;
        } else if (++short_lives_ >= 2) {
            return true;
        }
        kept_since_rebuild_ = 0;
        return false;
    }

private:
    std::size_t kept_since_rebuild_ = tuning::short_skin_life;  // the first build ends no life
    std::size_t short_lives_ = 0;                               // running
};

}  // namespace smb::detail
