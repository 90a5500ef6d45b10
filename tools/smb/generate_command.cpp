// SPDX-License-Identifier: MIT
#include "generate_command.hpp"

#include <fmt/format.h>

#include <exception>
#include <iostream>

#include "counted.hpp"
#include "file_streams.hpp"
#include "scene_csv.hpp"

namespace smb::cli {

namespace {

template <int Dim>
void write_environment(const EnvironmentOptions& options, std::ostream& out, std::size_t& final_count,
                       double& cube_side) {
    workload::DynamicEnvironment<Dim> environment(options.params());
    io::SceneWriter writer(out, Dim);
    for (std::size_t frame = 0; frame < options.steps; ++frame) {
        if (frame > 0) environment.step();
        writer.write_frame<Dim>(frame, environment.ids(), environment.boxes());
    }
    writer.flush();
    final_count = environment.size();
    cube_side = environment.cube_side();
}

}  // namespace

GenerateCommand::GenerateCommand(CLI::App& parent)
    : app_(parent.add_subcommand("generate",
                                 "Write the paper's artificial dynamic environment as a scene CSV "
                                 "(frame 0 is the initial placement)")) {
    environment_.box_count = 1000;
    environment_.steps = 10;
    add_environment_options(*app_, environment_);
    app_->add_option("-o,--output", output_,
                     "scene CSV to write ('-' for standard output); a file is replaced only on "
                     "success, a symbolic link's target is written, a FIFO or device is written "
                     "into")
        ->capture_default_str();
}

int GenerateCommand::run() const {
    io::OutputFile output(output_);
    std::size_t final_count = 0;
    double cube_side = 0;
    try {
        if (environment_.dimension == 2) {
            write_environment<2>(environment_, output.stream(), final_count, cube_side);
        } else {
            write_environment<3>(environment_, output.stream(), final_count, cube_side);
        }
    } catch (const std::exception&) {
        output.throw_if_failed();  // a failed write is said with its destination
        throw;
    }
    output.commit();
    if (!output.is_standard_output()) {
        std::cerr << fmt::format("smb generate: {} of {}D boxes, N {} -> {}, cube side {:.6g}, written to {}\n",
                                 counted(environment_.steps, "frame"), environment_.dimension, environment_.box_count,
                                 final_count, cube_side, output_);
    }
    return 0;
}

}  // namespace smb::cli
