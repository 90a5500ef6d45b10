// SPDX-License-Identifier: MIT
#pragma once
// Tuning of a World (WorldSettings) and of a Detector (DetectorSettings), and what they share
// (DetectionSettings). Every field has a default that suits the paper's workloads; a
// default-constructed settings object is the recommended start.

#include <cstddef>

namespace smb {

/// How a World finds its pairs. Both are exact and report the same pairs; they differ in speed
/// and in how closely they follow the paper's data structures (docs/algorithm.md).
enum class Pipeline {
    /// The default: the paper's levels of axial cuts, with the cut planes kept from one step to
    /// the next, so that each level is a linear bucketing pass, and a sweep inside every cell.
    persistent_cuts,
    /// The paper's Section 3 as written: corner lists sorted by DIS on every level, cut afresh
    /// each step, flag matrix and mask array. Slower; kept to reproduce the paper.
    paper_lists,
};

/// How Pipeline::paper_lists cuts each sorted section into segments (the paper's sub-lists).
enum class SegmentRule {
    /// The default: about (N / target_cell_population)^(1/Dim) segments per section on every
    /// level, of (nearly) equal counts, whatever the boxes' sizes. A box that spans more than two
    /// segments on some level is checked apart (docs/algorithm.md, deviation 3).
    from_count,
    /// The paper's own rule (its remark 4 of Section 2.4): the same number of segments at most,
    /// and every segment but a section's last at least twice as long, on its level's axis, as the
    /// largest extent of any box on that axis, so that no box spans more than two segments. A
    /// segment that would be shorter takes items from the next ones, leaving empty segments at
    /// the section's end. A box as long as the scene on some axis thus leaves one segment per
    /// section on that axis (a floor under a pile: one cell per slab, checked by a sweep), which
    /// the paper avoids by splitting such boxes beforehand.
    twice_largest_box,
};

/// What World and Detector both take: the axial cuts, the way pairs are handed over, the
/// threads. Not used on its own: a World takes WorldSettings, a Detector DetectorSettings.
struct DetectionSettings {
    /// Number of boxes the axial cut aims to put in one cell. The number of cuts per axis is
    /// derived from it: about (N / target_cell_population)^(1/Dim) segments on each axis.
    /// At least 1.
    std::size_t target_cell_population = 24;

    /// Number of pairs handed to a PairSink in one call of detect(sink). At least 1.
    std::size_t pair_chunk_size = 4096;

    /// Most pairs detect(..., std::vector<Pair>&) may collect (2^28 pairs are 4 GiB). Past it,
    /// it throws PairLimitError instead of exhausting memory; detect(sink) has no limit, since
    /// the caller consumes the pairs chunk by chunk. 100 000 identical boxes make 5·10^9 pairs.
    std::size_t max_pairs_held = std::size_t{1} << 28;

    /// Threads detect() may use (OpenMP): 1 runs on the calling thread alone, 0 takes as many
    /// as OpenMP offers (OMP_NUM_THREADS, else the cores). The pairs and their order are the
    /// same whatever the number. One by default, so that a simulation that already runs a
    /// thread or a process per core is not oversubscribed. Without OpenMP at build time
    /// (smb::openmp_enabled() is false), every value means one; so does a World with
    /// Pipeline::paper_lists. At most 1024: a larger value is refused with smb::ArgumentError.
    std::size_t threads = 1;

    /// Whether each detection fills a DetectProfile (World::last_profile(),
    /// Detector::last_profile()): its phases' seconds and the pipelines' counts. Off, the
    /// default, a detection reads the clock only for DetectStats::total_seconds.
    bool profile = false;
};

/// Tuning of a World: the shared DetectionSettings and the choice of pipeline.
struct WorldSettings : DetectionSettings {
    /// Which pipeline detects the pairs.
    Pipeline pipeline = Pipeline::persistent_cuts;
    /// How Pipeline::paper_lists chooses its segments; the persistent cuts do not read it.
    SegmentRule segment_rule = SegmentRule::from_count;
    /// The skin, as DetectorSettings::skin says: 0, the default, detects from scratch at every
    /// call; a positive skin keeps the pairs of fat boxes as candidates from one detection to
    /// the next, for the world's boxes, its filtered and its periodic detections alike. Needs
    /// Pipeline::persistent_cuts. Must be finite and not negative.
    double skin = 0;
};

/// Tuning of a Detector: the shared DetectionSettings and the skin. A Detector always detects
/// with the persistent cuts (Pipeline::persistent_cuts).
struct DetectorSettings : DetectionSettings {
    /// How far, in the boxes' own units, each box is grown on every side to make a fat box.
    /// 0, the default, detects from scratch at every call. A positive skin keeps the pairs of
    /// fat boxes that overlap as candidates from one call to the next (a Verlet list): while
    /// every box stays inside its fat box, a detection only tests the candidates, and the boxes
    /// that left their fat box (or arrived) look for new ones. Worth it when boxes move much
    /// less than the skin per call (a DEM code's "neighbour skin"; about the distance a body
    /// travels in 10 to 50 steps, and a fraction of its size): the candidates grow with the
    /// skin, the refreshes shrink. It holds about 40 bytes per box more, plus 8 per candidate.
    /// Where a quarter of the boxes leave their fat box in one step, the candidates keep being
    /// rebuilt (boxes that move farther than the skin) or would pass 32 per box, the detector
    /// steps aside for 64 detections and detects without the skin. Must be finite and not
    /// negative.
    double skin = 0;
};

/// True when this build of smb can use more than one thread (it was compiled with OpenMP).
[[nodiscard]] bool openmp_enabled() noexcept;

}  // namespace smb
