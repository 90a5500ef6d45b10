// SPDX-License-Identifier: MIT
#include "pairs_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdint>
#include <exception>
#include <iostream>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#ifdef SMB_CLI_HAS_MPI
#include "distributed_pairs.hpp"
#endif
#include "event_csv.hpp"
#include "file_streams.hpp"
#include "option_checks.hpp"
#include "pair_csv.hpp"
#include "periodic_pairs.hpp"
#include "scene_csv.hpp"
#include "scene_follower.hpp"
#include "smb/pair_events.hpp"
#include "smb/world.hpp"
#include "spilling_pair_sorter.hpp"

namespace smb::cli {

namespace {

// One World follows the scene through all its frames, so that detection profits from the small
// motion between frames exactly as a simulation would; the file is read one frame at a time.
// A frame's pairs stream from the world into a sorter that spills to temporary files past
// `pairs_in_memory`, so that a frame with billions of pairs costs disk, not memory.
template <int Dim>
void write_pairs_of_every_frame(io::SceneReader& reader, std::ostream& out, std::size_t pairs_in_memory) {
    World<double, Dim> world;
    io::SpillingPairSorter sorter(pairs_in_memory);
    io::PairWriter writer(out);
    io::SceneFollower<Dim> scene(reader);
    while (scene.advance(world)) {
        world.detect([&](std::span<const Pair> chunk) { sorter.add(chunk); });
        sorter.finish([&](std::span<const Pair> sorted) { writer.write_frame(scene.frame_number(), sorted); });
    }
    writer.flush();
}

// The same World through the frames, with PairEvents beside it. A frame's pairs are held in
// memory (the events compare whole lists), so --pairs-in-memory does not apply. A skipped frame
// number after a present frame is an empty frame: every pair ends there, under its number.
template <int Dim>
void write_events_of_every_frame(io::SceneReader& reader, std::ostream& out) {
    World<double, Dim> world;
    PairEvents events;
    std::vector<Pair> pairs;
    io::EventWriter writer(out);
    io::SceneFollower<Dim> scene(reader);

    const auto detect = [&](std::uint64_t number) {
        pairs.clear();
        try {
            world.detect(pairs, events);
        } catch (const PairLimitError&) {
            throw std::runtime_error("frame " + std::to_string(number) + " has more than " +
                                     std::to_string(world.settings().max_pairs_held) +
                                     " overlapping pairs, more than --events holds in memory");
        }
        writer.write_frame(number, events.begun(), events.ended());
    };
    while (scene.advance(world, detect)) detect(scene.frame_number());
    writer.flush();
}

}  // namespace

PairsCommand::PairsCommand(CLI::App& parent)
    : app_(parent.add_subcommand("pairs",
                                 "Find the overlapping pairs of every frame of a scene CSV "
                                 "and write them as a pair CSV")) {
    app_->add_option("-i,--input", input_, "scene CSV to read ('-' for standard input)")->capture_default_str();
    app_->add_option("-o,--output", output_,
                     "pair CSV to write ('-' for standard output); a file is replaced only on "
                     "success, a symbolic link's target is written, a FIFO or device is written "
                     "into")
        ->capture_default_str();
    app_->add_option("--pairs-in-memory", pairs_in_memory_,
                     "most pairs of one frame held in memory (16 bytes each); a frame with more "
                     "is sorted through temporary files")
        ->check(at_least(2))
        ->capture_default_str();
    auto* events = app_->add_flag("--events", events_,
                                  "write the pairs that begin and end overlapping at each frame, as an event "
                                  "CSV, instead of the pairs; holds a frame's pairs in memory");
    app_->add_option("--periodic", periodic_,
                     "X0:X1,Y0:Y1[,Z0:Z1]: the axes wrap around over [X0, X1) and so on ('-': an axis that "
                     "does not); writes the periodic pair CSV, with each pair's image shift")
        ->check([](const std::string& text) {
            try {
                (void)parse_periodic_axes(text);
            } catch (const std::invalid_argument& problem) {
                return std::string(problem.what());
            }
            return std::string();
        })
        ->excludes(events);
#ifdef SMB_CLI_HAS_MPI
    app_->add_flag("--distributed", distributed_,
                   "find the pairs over the ranks of an MPI run (mpirun -np P smb pairs --distributed ...): rank 0 "
                   "reads the scene and deals its rows round-robin, rank 0 writes the same pair CSV")
        ->excludes(events)
        ->excludes("--periodic");
#endif
    app_->footer([] {
        return fmt::format(
            "Scene CSV: header {} (3D) or {} (2D); one row per box per frame, frame numbers "
            "non-decreasing, an id once per frame; a skipped frame number is an empty frame.\n"
            "Pair CSV: header frame,a,b; one row per overlapping pair (touching counts), a < b, "
            "sorted by (frame, a, b).\n"
            "Event CSV (--events): header frame,a,b,event; event is begin (the pair overlaps at "
            "this frame and did not at the frame before) or end (the other way round; a removed box "
            "ends its pairs, the first skipped frame number ends every pair); every pair of the "
            "first frame begins; sorted by (frame, a, b, event).\n"
            "Periodic pair CSV (--periodic): header frame,a,b,sx,sy[,sz]; s is the image shift of b "
            "relative to a (a overlaps b translated by s periods; 0 on an axis that is not periodic); "
            "a box's extent on a periodic axis must be below half the period; sorted by (frame, a, b).\n"
            "A malformed line stops the run with 'file:line: problem' on standard error.\n",
            io::scene_header(3), io::scene_header(2));
    });
}

int PairsCommand::run() const {
#ifdef SMB_CLI_HAS_MPI
    if (distributed_) return run_distributed_pairs(input_, output_);
#endif
    // Run without --input from a terminal, pairs would wait for typed input without a word.
    if (input_ == "-" && ::isatty(STDIN_FILENO) == 1) {
        std::cerr << "smb pairs: reading a scene CSV from standard input (end it with Ctrl-D; "
                     "--input FILE reads a file)\n";
    }
    io::InputFile input(input_);
    io::SceneReader reader(input.stream(), input.name());
    io::OutputFile output(output_);
    try {
        if (!periodic_.empty()) {
            write_periodic_pairs(reader, output.stream(), parse_periodic_axes(periodic_));
        } else if (events_) {
            if (reader.dimension() == 2) {
                write_events_of_every_frame<2>(reader, output.stream());
            } else {
                write_events_of_every_frame<3>(reader, output.stream());
            }
        } else if (reader.dimension() == 2) {
            write_pairs_of_every_frame<2>(reader, output.stream(), pairs_in_memory_);
        } else {
            write_pairs_of_every_frame<3>(reader, output.stream(), pairs_in_memory_);
        }
    } catch (const std::exception&) {
        output.throw_if_failed();  // a failed write is said with its destination
        throw;
    }
    output.commit();
    return 0;
}

}  // namespace smb::cli
