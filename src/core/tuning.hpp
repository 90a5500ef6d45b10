// SPDX-License-Identifier: MIT
#pragma once
// The tuning constants of every part, each with the reason for its value. They change speed or
// memory, never the pairs. Limits the data layout imposes (bits in a packed key, lanes in a
// register) stay beside the code they bound; so do prefetch distances, one loop's each.

#include <cstddef>
#include <cstdint>

#include "smb/settings.hpp"

namespace smb::detail::tuning {

// --- Memory (src/core/bulk_vector.hpp) ------------------------------------------------------

/// Blocks from this size on have their pages mapped in one call (256 pages, about 3 ms of faults
/// on a virtual machine); smaller ones come and go from memory the process holds mapped already.
inline constexpr std::size_t mapped_at_once_from = std::size_t{1} << 20;

// --- The axial cuts (src/cuts/) --------------------------------------------------------------

/// Boxes the cuts aim to put in one cell (DetectionSettings::target_cell_population's default):
/// 16, 20, 24 and 32 gave steps within 1% at 1M boxes (docs/algorithm.md, "Design decisions").
inline constexpr std::size_t cell_population = 24;
static_assert(DetectionSettings{}.target_cell_population == cell_population);
/// Cells of up to this many registered boxes test every pair, past it they are swept: every pair
/// is faster at the usual ~46 boxes and still at ~130 (target population 64), but costs m^2 / 16.
inline constexpr std::size_t all_pairs_limit = 128;
/// A column whose rows reach this many boxes along x or more (CellXOrder::reach(), a bound from
/// its widest box) is swept two groups of lanes a turn, else one. The paper's 3D columns reach
/// about 13: two a turn took its check about 5% less time; 2D columns reach about 5, and there
/// two a turn took 12% more, sparse 3D columns 7% more (smb_compare --method smb, 300k boxes).
inline constexpr double long_sweep_rows = 10.0;
/// Pairs one column may hold while the threads check a round (4 MiB a thread): a column that
/// makes more is checked again on the calling thread straight into the report, so that the
/// buffers stay bounded whatever the output.
inline constexpr std::size_t block_pair_cap = std::size_t{1} << 18;
/// Boxes sampled for a group's typical extent: enough to place the band, cheap on every group.
inline constexpr std::size_t extent_sample = 64;
/// A group with more than twice this many keys per segment takes its quantiles from an even
/// sample of this many per segment: within about 6% of the true quantiles (the band is measured
/// on the real counts), and the first cuts at 1M boxes (1M keys on level 0, 28k per group on
/// level 1) several times cheaper.
inline constexpr std::size_t sample_per_segment = 256;
/// Below this many keys the recursive quantile selection beats the radix sort (selection against
/// radix: 64 keys 0.08 against 0.71 µs, 128 keys 2.9 against 0.94, 1000 keys 42 against 4.4,
/// double 41 against 9.4; uniform floats, k = max(2, n / 24), fresh keys at every call, since a
/// repeated input lets the branch predictor flatter the selection 6×; bench/bench_quantiles.cpp).
inline constexpr std::size_t quantile_radix_from = 128;
/// A level above the columns whose planes, kept a box apart, leave open fewer than this share of
/// its segments is a layer a few boxes thick: it keeps what it can open, the other level takes
/// the rest (src/cuts/sampled_cuts.hpp). Three quarters: a level that loses a segment or two to
/// a crowd of large boxes keeps its shape.
inline constexpr double thin_level_open_share = 0.75;
/// Such a layer that opens at most this many segments is left whole, and the other level takes
/// every column. Its segments would be about a box thick, so that most boxes registered in two,
/// while the other level, its planes a box apart too, cannot open the segments it is given. On
/// boxes of sides 0.4 to 1 whose centres keep to a slab (`smb_compare --scene plane`, 300k, 3D,
/// Detector, the slab made thicker for the test): 2 thick (3 open), whole 1.51 registrations a box
/// against 1.81 and 15.5 against 18.6 ms a step; 6 thick (6 open), 1.60 against 2.09 and 17.9
/// against 21.7 ms; 10 thick (10 open), whole was slower (23.4-24.1 against 20.2-21.5 ms): its
/// columns' cross-sections hold too many candidates.
inline constexpr double whole_layer_open = 6.0;
/// The boxes are copied grouped by column (src/cuts/column_presort.hpp) once the first level's
/// hint misses on more than this share of its entries. At 1M boxes in 3D (`smb run --pipeline
/// detector`) it missed on 2% at Λ = 0.01, 7% at 0.02, 14% at 0.03, 62% at 0.1; a step copied by
/// column took 94-97 ms against 100-105 in last step's order at 0.02, 92-96 against 106-109 at
/// 0.03, 99-103 against 107-112 at 0.1 (copy 8-10 ms dearer, levels 13-14 ms cheaper). Below
/// about 5% last step's order, x-sorted in each column, serves better.
inline constexpr double column_copy_start_misses = 0.05;
/// It stops once fewer than this share of the sampled boxes changed column since the last such
/// copy: a kept order then reads most columns in one run.
inline constexpr double column_copy_stop_changed = 0.5;
/// One box in this many is sampled for that share: 62,500 at 1M, for a sixteenth of a locate a box.
inline constexpr std::size_t column_copy_sample_stride = 16;
/// Detections between two judgements of floats against doubles (points may grow into boxes):
/// judging costs a pass over the boxes, one in 64 is noise.
inline constexpr std::size_t judge_precision_every = 64;

// --- The skin (src/skin/, src/engine/) -------------------------------------------------------

/// Detections the cuts run after the skin stepped aside before it tries again: a failed retry
/// costs one rebuild, paid at most once in 64 detections.
inline constexpr std::size_t skin_pause = 64;
/// The moved list is tested against every fresh box: past max(64, n / 64) entries a rebuild of
/// the cells costs less than those tests.
inline constexpr std::size_t moved_limit_floor = 64;
inline constexpr std::size_t moved_limit_divisor = 64;
/// Fewer detections than this between two rebuilds make a short life: the skin is too thin for
/// the motion, and the pipelines detect instead.
inline constexpr std::size_t short_skin_life = 4;
/// Candidates per box (plus 2^20) past which the skin steps aside: fat boxes that crowd are too
/// fat for the scene, and the candidates' memory and tests outgrow a detection without them.
inline constexpr std::size_t skin_candidates_per_box = 32;
/// Candidates below which a pass over them runs on one thread (a fork costs more), and those of
/// one thread's block otherwise.
inline constexpr std::size_t skin_parallel_from = std::size_t{1} << 15;
inline constexpr std::size_t skin_block_candidates = std::size_t{1} << 15;

// --- Statics and filters (src/filters/) ------------------------------------------------------

/// A moving box's cached statics are held on a lattice of 16-bit steps over its fat box: a copy
/// is a quarter of the float box, and the lattice test tells nearly every static apart.
inline constexpr double static_lattice_top = 32767;
/// Detections between two counts of the filter values once they overflowed the classes' table
/// (they may have become fewer): a count costs a pass over the boxes.
inline constexpr std::size_t filter_classes_every = 64;

// --- The grid (src/query/grid_index.hpp: the queries' index and the statics') ----------------

/// Most cells per box (plus 16) of the finest level: memory O(N) whatever the region, and cells
/// near the mean box where the boxes fill it.
inline constexpr double grid_cells_per_box = 2;
/// The finest side grows by this factor until that level fits its budget: fine steps keep the
/// cells near the mean box.
inline constexpr double grid_side_growth = 1.25;
/// Moving boxes with no size get a skin of an eighth of this many finest cells of the statics'
/// grid (about twice the mean static), so that a point does not refresh its statics every step.
inline constexpr double static_cell_in_means = 2;

// --- Pair keys and events (src/core/pair_key_sort.hpp, src/events/) --------------------------

/// Below this many pairs std::sort beats the radix sort's fixed passes over its counts.
inline constexpr std::size_t radix_sort_from = 2048;
/// The widest digit of the pair keys' radix sort. A pass scatters the keys to as many places as
/// its digit has values: at 10 bits those stay in a core's cache, at 14 they miss, which costs
/// more than the pass saved. A 40-bit key (a million names) takes four passes of 10 bits: 1.6M
/// random keys in 26 ms against 46 ms in three of 14, 50k keys of 28 bits alike (0.69 and 0.72 ms).
inline constexpr int radix_digit_bits = 11;
/// Pairs per partition of the events' diff: their table (32 slots a pair, 4 bytes a slot) and
/// the pairs fit in a core's L2 cache.
inline constexpr std::size_t pairs_per_partition = 1024;
/// The gapped layout gives each partition its mean plus this many standard deviations (the hash
/// spreads pairs as a Poisson process would); the rare overflow goes to a spill list.
inline constexpr std::size_t partition_slack_deviations = 4;
/// Pairs per thread below which the events lay out the list on one thread.
inline constexpr std::size_t event_pairs_per_thread = std::size_t{1} << 16;

// --- The Bullet back end (src/bullet/) -------------------------------------------------------

/// A proxy that kept inside its fat box this many steps before leaving it creeps.
inline constexpr std::uint32_t bullet_steps_before_creeping = 16;
/// A creeping proxy's skin, in skins: a pile at rest creeps, each box leaving a one-skin fat box
/// every hundred steps or so at the cost of an index query and a pass over the candidates; a
/// thicker skin holds it several times as long.
inline constexpr float bullet_creeping_skins = 2;
/// A static-class proxy that moved is held dynamic until it has kept still this many steps, so
/// that a kinematic body pushed every step does not make smb index its statics again each step.
inline constexpr std::uint32_t bullet_steps_before_static = 8;

// --- The paper's pipeline (src/paper/) -------------------------------------------------------

/// Above this many boxes a cell is checked by the sweep alone, not the paper's flag matrix of
/// m^2 bytes: such a crowd (boxes sharing a coordinate no cut splits) costs the sweep only its
/// output.
inline constexpr std::size_t paper_matrix_max_boxes = 256;

// --- Joins (src/join/) -----------------------------------------------------------------------

/// Most cells per axis of the grid that culls the larger set of a join: past it the marking by
/// large boxes costs more than the cull saves (2D: 2048, 3D: 160, about four million cells).
inline constexpr std::size_t join_cull_cells_2d = 2048;
inline constexpr std::size_t join_cull_cells_3d = 160;

}  // namespace smb::detail::tuning
