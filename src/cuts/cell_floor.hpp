// SPDX-License-Identifier: MIT
#pragma once

#include <array>
#include <concepts>

namespace smb::detail {

/// Lower planes of a cell on every axis (-inf where the cell is first on that axis): what the
/// cell check needs to report a pair shared by several cells in one of them only.
template <std::floating_point Real, int Dim>
using CellFloor = std::array<Real, Dim>;

}  // namespace smb::detail
