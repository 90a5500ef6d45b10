// SPDX-License-Identifier: MIT
#include "join_command.hpp"

#include <fmt/format.h>

#include <array>
#include <exception>
#include <span>
#include <vector>

#include "csv_error.hpp"
#include "file_streams.hpp"
#include "frame_diff.hpp"
#include "join_ids.hpp"
#include "option_checks.hpp"
#include "pair_csv.hpp"
#include "scene_csv.hpp"
#include "smb/world.hpp"
#include "spilling_pair_sorter.hpp"

namespace smb::cli {

namespace {

constexpr std::array<io::JoinSide, 2> sides{io::JoinSide::left, io::JoinSide::right};

/// The changes of both scenes between two frames, applied to one World in internal ids: every
/// removal first (which frees internal ids), then the updates, then the insertions.
template <int Dim>
class JoinedWorld {
public:
    void clear() {
        world_.clear();
        ids_.clear();
    }

    void apply(const std::array<io::FrameChanges<Dim>, 2>& changes) {
        batch_.clear();
        for (const io::JoinSide side : sides) {
            for (const BoxId id : changes[index(side)].removed_ids) batch_.push_back(ids_.find(side, id));
        }
        world_.remove(batch_);
        for (const io::JoinSide side : sides) {
            for (const BoxId id : changes[index(side)].removed_ids) ids_.release(side, id);
        }
        for (const io::JoinSide side : sides) {
            const auto& side_changes = changes[index(side)];
            batch_.clear();
            for (const BoxId id : side_changes.updated_ids) batch_.push_back(ids_.find(side, id));
            world_.update(batch_, side_changes.updated_boxes);
        }
        for (const io::JoinSide side : sides) {
            const auto& side_changes = changes[index(side)];
            batch_.clear();
            for (const BoxId id : side_changes.inserted_ids) batch_.push_back(ids_.add(side, id));
            world_.insert(batch_, side_changes.inserted_boxes);
        }
    }

    /// Hands the pairs with one box in each scene to `sink` as (left id, right id), in chunks.
    template <class Sink>
    void detect_cross_pairs(Sink&& sink) {
        world_.detect([&](std::span<const Pair> chunk) {
            cross_.clear();
            for (const Pair& pair : chunk) {
                const io::JoinSide side_a = ids_.side(pair.a);
                if (side_a == ids_.side(pair.b)) continue;
                const BoxId a = ids_.id(pair.a);
                const BoxId b = ids_.id(pair.b);
                cross_.push_back(side_a == io::JoinSide::left ? Pair{a, b} : Pair{b, a});
            }
            sink(std::span<const Pair>(cross_));
        });
    }

private:
    static std::size_t index(io::JoinSide side) { return static_cast<std::size_t>(side); }

    World<double, Dim> world_;
    io::JoinIds ids_;
    std::vector<BoxId> batch_;
    std::vector<Pair> cross_;
};

// One World follows both scenes through all their frames (temporal coherence, as `smb pairs`),
// each file read one frame at a time; frames are matched by number. The pairs within one scene
// are detected too and dropped: the persistent two-set form is one world with filters.
template <int Dim>
void write_join_of_every_frame(std::array<io::SceneReader*, 2> readers, std::ostream& out,
                               std::size_t pairs_in_memory) {
    JoinedWorld<Dim> world;
    io::SpillingPairSorter sorter(pairs_in_memory);
    io::PairWriter writer(out, "frame,left,right");
    std::array<io::SceneFrame<Dim>, 2> frames;
    std::array<bool, 2> pending{};
    std::array<std::vector<BoxId>, 2> previous_ids;
    std::array<io::FrameChanges<Dim>, 2> changes;
    const io::SceneFrame<Dim> absent;  // a frame a scene lacks: empty on that side
    for (std::size_t s = 0; s < 2; ++s) pending[s] = readers[s]->read_frame(frames[s]);
    bool first_frame = true;
    std::uint64_t previous_number = 0;

    while (pending[0] || pending[1]) {
        std::uint64_t number = pending[0] ? frames[0].number : frames[1].number;
        if (pending[1] && frames[1].number < number) number = frames[1].number;
        // A frame number neither scene has is empty on both sides: everything was deleted.
        if (!first_frame && number > previous_number + 1) {
            world.clear();
            previous_ids[0].clear();
            previous_ids[1].clear();
        }
        std::array<bool, 2> present{};
        for (std::size_t s = 0; s < 2; ++s) {
            present[s] = pending[s] && frames[s].number == number;
            io::diff_frames<Dim>(previous_ids[s], present[s] ? frames[s] : absent, changes[s]);
        }
        world.apply(changes);
        world.detect_cross_pairs([&](std::span<const Pair> chunk) { sorter.add(chunk); });
        sorter.finish([&](std::span<const Pair> sorted) { writer.write_frame(number, sorted); });

        for (std::size_t s = 0; s < 2; ++s) {
            if (present[s]) {
                previous_ids[s].swap(frames[s].ids);
                pending[s] = readers[s]->read_frame(frames[s]);
            } else {
                previous_ids[s].clear();
            }
        }
        previous_number = number;
        first_frame = false;
    }
    writer.flush();
}

}  // namespace

JoinCommand::JoinCommand(CLI::App& parent)
    : app_(parent.add_subcommand("join",
                                 "Find the overlapping pairs between the boxes of two scene CSVs, frame by "
                                 "frame, and write them as a join CSV")) {
    app_->add_option("-l,--left", left_, "scene CSV of the left set ('-' for standard input)")->required();
    app_->add_option("-r,--right", right_, "scene CSV of the right set ('-' for standard input)")->required();
    app_->add_option("-o,--output", output_,
                     "join CSV to write ('-' for standard output); a file is replaced only on "
                     "success, a symbolic link's target is written, a FIFO or device is written "
                     "into")
        ->capture_default_str();
    app_->add_option("--pairs-in-memory", pairs_in_memory_,
                     "most pairs of one frame held in memory (16 bytes each); a frame with more "
                     "is sorted through temporary files")
        ->check(at_least(2))
        ->capture_default_str();
    app_->footer([] {
        return fmt::format(
            "Scene CSV: header {} (3D) or {} (2D); both files of the same dimension. Frames are "
            "matched by number; a frame one file lacks is empty on that side. The two files' ids "
            "are separate name spaces.\n"
            "Join CSV: header frame,left,right; one row per overlapping pair (touching counts) of a "
            "box of the left file and one of the right file, sorted by (frame, left, right).\n"
            "A malformed line in either file stops the run with 'file:line: problem' on standard "
            "error.\n",
            io::scene_header(3), io::scene_header(2));
    });
}

int JoinCommand::run() const {
    if (left_ == "-" && right_ == "-")
        throw CLI::ValidationError("--left, --right", "at most one of them can be standard input ('-')");
    io::InputFile left_input(left_);
    io::InputFile right_input(right_);
    io::SceneReader left(left_input.stream(), left_input.name());
    io::SceneReader right(right_input.stream(), right_input.name());
    if (left.dimension() != right.dimension()) {
        throw io::CsvError(right.source_name(), 1,
                           fmt::format("a {}D scene, but the left scene {} is {}D: both scenes must have "
                                       "the same dimension",
                                       right.dimension(), left.source_name(), left.dimension()));
    }
    io::OutputFile output(output_);
    try {
        if (left.dimension() == 2) {
            write_join_of_every_frame<2>({&left, &right}, output.stream(), pairs_in_memory_);
        } else {
            write_join_of_every_frame<3>({&left, &right}, output.stream(), pairs_in_memory_);
        }
    } catch (const std::exception&) {
        output.throw_if_failed();  // a failed write is said with its destination
        throw;
    }
    output.commit();
    return 0;
}

}  // namespace smb::cli
