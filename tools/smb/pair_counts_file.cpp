// SPDX-License-Identifier: MIT
#include "pair_counts_file.hpp"

#include <fmt/format.h>

#include "file_streams.hpp"

namespace smb::cli {

void write_pair_counts(const RunRecord& run, const std::string& path) {
    io::OutputFile output(path);
    std::ostream& out = output.stream();
    out << "step,pairs\n";
    for (std::size_t step = 0; step < run.steps.size(); ++step)
        out << fmt::format("{},{}\n", step + 1, run.steps[step].stats.pairs);
    output.throw_if_failed();
    output.commit();
}

}  // namespace smb::cli
