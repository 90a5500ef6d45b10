// SPDX-License-Identifier: MIT
#pragma once
// The scene CSV of the smb conventions: header `frame,id,xmin,ymin,zmin,xmax,ymax,zmax` (3D) or
// `frame,id,xmin,ymin,xmax,ymax` (2D), one row per box per frame, frames non-decreasing.

#include <array>
#include <cstdint>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "line_reader.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::io {

/// The boxes of one frame, sorted by id.
template <int Dim>
struct SceneFrame {
    std::uint64_t number = 0;
    std::vector<BoxId> ids;
    std::vector<Box<double, Dim>> boxes;
    std::vector<std::uint64_t> lines;  ///< input line of each box, for messages

    void clear() {
        ids.clear();
        boxes.clear();
        lines.clear();
    }
};

/// Reads a scene CSV frame by frame, holding one frame (and the first row of the next) at a
/// time. Every problem is thrown as CsvError naming the source and line: a missing or unknown
/// header, a wrong number of fields, a field that is not a number, a negative or too large
/// integer, NaN or infinity, min > max, an id twice in one frame, frames out of order.
/// Accepts CRLF line ends, a missing final newline, a UTF-8 byte order mark, spaces around
/// fields and blank lines (skipped).
class SceneReader {
public:
    /// Reads the header. `source_name` is used in messages only.
    SceneReader(std::istream& in, std::string source_name);

    /// 2 or 3, from the header.
    [[nodiscard]] int dimension() const noexcept { return dimension_; }
    [[nodiscard]] const std::string& source_name() const noexcept { return source_name_; }

    /// Reads the next frame into `frame`; false at the end of input. Dim must equal dimension().
    /// Frame numbers that the file skips are empty frames; they are not returned.
    template <int Dim>
    bool read_frame(SceneFrame<Dim>& frame);

private:
    struct Row {
        std::uint64_t frame = 0;
        BoxId id = 0;
        std::array<double, 6> coordinates{};  // the mins, then the maxes
        std::uint64_t line = 0;
    };

    void read_header();
    bool read_row(Row& row);
    [[noreturn]] void fail(std::uint64_t line, const std::string& problem) const;
    template <int Dim>
    void sort_and_check_ids(SceneFrame<Dim>& frame) const;

    LineReader lines_;
    std::string source_name_;
    int dimension_ = 0;
    std::vector<std::string_view> fields_;
    Row pending_;
    bool has_pending_ = false;
};

/// Writes a scene CSV. Coordinates are printed in the shortest form that reads back to the
/// same double, so a written scene round-trips exactly.
class SceneWriter {
public:
    SceneWriter(std::ostream& out, int dimension);
    ~SceneWriter();
    SceneWriter(const SceneWriter&) = delete;
    SceneWriter& operator=(const SceneWriter&) = delete;

    template <int Dim>
    void write_frame(std::uint64_t frame, std::span<const BoxId> ids, std::span<const Box<double, Dim>> boxes);
    /// Hands everything buffered to the stream; throws std::runtime_error if the stream failed.
    void flush();

private:
    std::ostream& out_;
    int dimension_;
    std::string buffer_;
};

/// The header line (without newline) for 2 or 3 dimensions.
[[nodiscard]] std::string_view scene_header(int dimension);

}  // namespace smb::io
