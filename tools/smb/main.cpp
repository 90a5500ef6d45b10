// smb: the command-line face of the library. Subcommands: pairs, generate, run.
// Exit status: 0 success, 1 bad input or I/O failure, 2 a detection that differs from the
// reference (smb run), CLI11's own codes for bad arguments.

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "generate_command.hpp"
#include "pairs_command.hpp"
#include "run_command.hpp"
#include "smb/version.hpp"

int main(int argc, char** argv) {
    std::ios::sync_with_stdio(false);

    CLI::App app("smb " SMB_VERSION_STRING
                 ": broad-phase collision detection of moving boxes (Sort Moving Boxes, "
                 "Li, Feng & Owen 2006)",
                 "smb");
    app.set_version_flag("--version", SMB_VERSION_STRING);
    app.require_subcommand(1);
    const smb::cli::PairsCommand pairs(app);
    const smb::cli::GenerateCommand generate(app);
    const smb::cli::RunCommand run(app);

    CLI11_PARSE(app, argc, argv);
    try {
        if (pairs.selected()) return pairs.run();
        if (generate.selected()) return generate.run();
        if (run.selected()) return run.run();
    } catch (const std::exception& error) {
        std::cout.flush();
        std::cerr << "smb: error: " << error.what() << '\n';
        return 1;
    }
    return 1;
}
