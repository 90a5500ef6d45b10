// SPDX-License-Identifier: MIT
// smb: the command-line face of the library. Subcommands: pairs, generate, run, join.
// Exit statuses: exit_status.hpp.

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <string_view>

#include "exit_status.hpp"
#include "file_streams.hpp"
#include "generate_command.hpp"
#include "join_command.hpp"
#include "pairs_command.hpp"
#include "run_command.hpp"
#include "smb/version.hpp"

namespace {

/// "pairs, generate, run": the names of the commands, as --help lists them.
std::string command_names(const CLI::App& app) {
    std::string names;
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
        if (!names.empty()) names += ", ";
        names += command->get_name();
    }
    return names;
}

/// The command the user named when it is not one of smb's; empty otherwise. CLI11 would only
/// say that a command is required, without naming what it got.
std::string unknown_command(const CLI::App& app, int argc, char** argv) {
    if (argc < 2) return {};
    const std::string first = argv[1];
    if (first.starts_with('-')) return {};
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; }))
        if (command->check_name(first)) return {};
    return first;
}

int argument_error(const CLI::App& app, const std::string& problem) {
    std::cout.flush();
    const auto selected = app.get_subcommands();
    const std::string help =
        selected.empty() ? std::string("smb --help") : "smb " + selected.front()->get_name() + " --help";
    std::cerr << "smb: error: " << problem << "\nRun '" << help << "' for more information.\n";
    return smb::cli::exit_status::usage;
}

}  // namespace

int main(int argc, char** argv) {
    namespace exit_status = smb::cli::exit_status;
    std::ios::sync_with_stdio(false);
    smb::io::keep_standard_output_errors();

    CLI::App app("smb " SMB_VERSION_STRING
                 ": broad-phase collision detection of moving boxes (Sort Moving Boxes, "
                 "Li, Feng & Owen 2006)",
                 "smb");
    app.set_version_flag("--version", SMB_VERSION_STRING);
    app.require_subcommand(1);
    app.footer(exit_status::summary);
    const smb::cli::PairsCommand pairs(app);
    const smb::cli::GenerateCommand generate(app);
    const smb::cli::RunCommand run(app);
    const smb::cli::JoinCommand join(app);

    if (argc < 2) return argument_error(app, "no command given; the commands are " + command_names(app));
    if (const std::string unknown = unknown_command(app, argc, argv); !unknown.empty()) {
        return argument_error(app, "unknown command '" + unknown + "'; the commands are " + command_names(app));
    }
    int status = exit_status::failure;
    try {
        try {
            app.parse(argc, argv);
        } catch (const CLI::ParseError& error) {
            if (error.get_exit_code() != 0) return argument_error(app, error.what());
            status = app.exit(error);  // --help or --version, printed on standard output
            smb::io::close_standard_output();
            return status;
        }
        if (pairs.selected()) status = pairs.run();
        if (generate.selected()) status = generate.run();
        if (run.selected()) status = run.run();
        if (join.selected()) status = join.run();
        // What was printed must have reached its destination, or the run failed.
        smb::io::close_standard_output();
    } catch (const CLI::Error& error) {
        // A check of the arguments together, made once they are parsed.
        return argument_error(app, error.what());
    } catch (const std::bad_alloc&) {
        std::cout.flush();
        std::cerr << "smb: error: not enough memory\n";
        return exit_status::failure;
    } catch (const std::exception& error) {
        std::cout.flush();
        std::cerr << "smb: error: " << error.what() << '\n';
        return exit_status::failure;
    }
    return status;
}
