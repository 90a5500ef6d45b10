// SPDX-License-Identifier: MIT
#pragma once
// Everything a user of smb needs.

#include "smb/box.hpp"
#include "smb/box_index.hpp"
#include "smb/detector.hpp"
#include "smb/errors.hpp"
#include "smb/filter.hpp"
#include "smb/held_precision.hpp"
#include "smb/join.hpp"
#include "smb/pair.hpp"
#include "smb/pair_events.hpp"
#include "smb/profile.hpp"
#include "smb/query.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"
#include "smb/version.hpp"
#include "smb/world.hpp"
