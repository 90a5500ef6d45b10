// SPDX-License-Identifier: MIT
#pragma once
// Running the built `smb` binary from end-to-end tests. SMB_CLI_PATH and SMB_CLI_DATA_DIR come
// from tests/tool/CMakeLists.txt.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace smb::cli_test {

namespace fs = std::filesystem;

inline fs::path data_file(const std::string& name) { return fs::path(SMB_CLI_DATA_DIR) / name; }

inline std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

inline void write_file(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

/// A fresh folder under the system's temporary folder, removed with everything in it.
class TempFolder {
public:
    TempFolder() {
        std::string pattern = (fs::temp_directory_path() / "smb-cli-test-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
        path_ = pattern;
    }
    ~TempFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;

    [[nodiscard]] const fs::path& path() const { return path_; }
    [[nodiscard]] fs::path operator/(const std::string& name) const { return path_ / name; }
    [[nodiscard]] std::size_t entry_count() const {
        return static_cast<std::size_t>(std::distance(fs::directory_iterator(path_), {}));
    }

private:
    fs::path path_;
};

struct CliResult {
    int status = -1;  ///< exit status, or -1 if the process did not exit normally
    std::string out;
    std::string err;
};

inline std::string shell_quoted(const std::string& text) {
    std::string quoted = "'";
    for (const char c : text) {
        if (c == '\'') {
            quoted += "'\\''";
        } else {
            quoted += c;
        }
    }
    return quoted + "'";
}

/// Runs smb with `arguments` in `folder` (its working directory), standard input from
/// `stdin_path` when given (else /dev/null), standard output into `stdout_path` when given (else
/// captured), and captures standard error.
inline CliResult run_smb_with(const TempFolder& folder, const std::vector<std::string>& arguments,
                              const fs::path& stdin_path, const fs::path& stdout_path) {
    const fs::path out_path = stdout_path.empty() ? folder / ".stdout" : stdout_path;
    const fs::path err_path = folder / ".stderr";
    // Built by appending only: GCC 12 misreads "literal" + std::string temporaries (-Wrestrict).
    std::string command = "cd ";
    command += shell_quoted(folder.path().string());
    command += " && ";
    command += shell_quoted(SMB_CLI_PATH);
    for (const auto& argument : arguments) {
        command += ' ';
        command += shell_quoted(argument);
    }
    command += " < ";
    command += shell_quoted(stdin_path.empty() ? "/dev/null" : stdin_path.string());
    command += " > ";
    command += shell_quoted(out_path.string());
    command += " 2> ";
    command += shell_quoted(err_path.string());
    const int raw = std::system(command.c_str());
    CliResult result;
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    if (stdout_path.empty()) {
        result.out = read_file(out_path);
        fs::remove(out_path);
    }
    result.err = read_file(err_path);
    fs::remove(err_path);
    return result;
}

/// Runs smb with `arguments` in `folder` (its working directory), standard input from
/// `stdin_path` when given (else /dev/null), and captures both output streams.
inline CliResult run_smb(const TempFolder& folder, const std::vector<std::string>& arguments,
                         const fs::path& stdin_path = {}) {
    return run_smb_with(folder, arguments, stdin_path, {});
}

}  // namespace smb::cli_test
