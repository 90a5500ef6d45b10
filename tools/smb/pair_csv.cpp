// SPDX-License-Identifier: MIT
#include "pair_csv.hpp"

#include <fmt/format.h>

#include <iterator>
#include <stdexcept>

#include "csv_error.hpp"
#include "csv_fields.hpp"
#include "line_reader.hpp"

namespace smb::io {

namespace {

constexpr std::string_view pair_header = "frame,a,b";

}  // namespace

PairWriter::PairWriter(std::ostream& out, std::string_view header) : out_(out) {
    buffer_.append(header);
    buffer_ += '\n';
}

PairWriter::~PairWriter() {
    try {
        flush();
    } catch (...) {
        // A destructor must not throw; callers who care about errors call flush() themselves.
    }
}

void PairWriter::write_frame(std::uint64_t frame, std::span<const Pair> pairs) {
    auto out = std::back_inserter(buffer_);
    for (const Pair& pair : pairs) {
        fmt::format_to(out, "{},{},{}\n", frame, pair.a, pair.b);
        if (buffer_.size() >= csv_flush_threshold) flush();
    }
}

void PairWriter::flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
    if (!out_) throw std::runtime_error("writing the pairs failed");
}

std::vector<FramePair> read_pair_csv(std::istream& in, const std::string& source_name) {
    LineReader lines(in);
    auto header = lines.next();
    if (!header) throw CsvError(source_name, 1, "empty file: expected the header 'frame,a,b'");
    if (*header != pair_header) {
        throw CsvError(source_name, 1, "unknown header " + quoted(*header) + ": expected 'frame,a,b'");
    }
    std::vector<FramePair> rows;
    std::vector<std::string_view> fields;
    while (auto line = lines.next()) {
        if (trim(*line).empty()) continue;
        const auto line_number = lines.line_number();
        split_fields(*line, fields);
        if (fields.size() != 3) {
            throw CsvError(source_name, line_number, fmt::format("expected 3 fields, found {}", fields.size()));
        }
        FramePair row;
        try {
            row.frame = parse_unsigned(fields[0], "frame");
            row.a = parse_unsigned(fields[1], "a");
            row.b = parse_unsigned(fields[2], "b");
        } catch (const std::invalid_argument& problem) {
            throw CsvError(source_name, line_number, problem.what());
        }
        if (row.a >= row.b) {
            throw CsvError(source_name, line_number, fmt::format("a {} is not less than b {}", row.a, row.b));
        }
        if (!rows.empty() && !(rows.back() < row)) {
            throw CsvError(source_name, line_number, "rows are not sorted by (frame, a, b) or repeat a pair");
        }
        rows.push_back(row);
    }
    return rows;
}

}  // namespace smb::io
