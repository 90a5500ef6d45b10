// SPDX-License-Identifier: MIT
#include "scene_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <numeric>
#include <stdexcept>

#include "csv_error.hpp"
#include "csv_fields.hpp"

namespace smb::io {

namespace {

constexpr std::string_view header_2d = "frame,id,xmin,ymin,xmax,ymax";
constexpr std::string_view header_3d = "frame,id,xmin,ymin,zmin,xmax,ymax,zmax";
constexpr std::string_view coordinate_names_2d[] = {"xmin", "ymin", "xmax", "ymax"};
constexpr std::string_view coordinate_names_3d[] = {"xmin", "ymin", "zmin", "xmax", "ymax", "zmax"};
constexpr std::string_view byte_order_mark = "\xEF\xBB\xBF";

}  // namespace

std::string_view scene_header(int dimension) { return dimension == 2 ? header_2d : header_3d; }

SceneReader::SceneReader(std::istream& in, std::string source_name) : lines_(in), source_name_(std::move(source_name)) {
    read_header();
}

void SceneReader::fail(std::uint64_t line, const std::string& problem) const {
    throw CsvError(source_name_, line, problem);
}

void SceneReader::read_header() {
    auto line = lines_.next();
    if (!line)
        fail(1, "empty file: expected the header '" + std::string(header_3d) + "' or '" + std::string(header_2d) + "'");
    std::string_view text = *line;
    if (text.starts_with(byte_order_mark)) text.remove_prefix(byte_order_mark.size());
    split_fields(text, fields_);
    std::string normalised;
    for (std::size_t i = 0; i < fields_.size(); ++i) {
        if (i > 0) normalised += ',';
        normalised += trim(fields_[i]);
    }
    if (normalised == header_3d) {
        dimension_ = 3;
    } else if (normalised == header_2d) {
        dimension_ = 2;
    } else {
        fail(lines_.line_number(), "unknown header " + quoted(text) + ": expected '" + std::string(header_3d) +
                                       "' or '" + std::string(header_2d) + "'");
    }
}

bool SceneReader::read_row(Row& row) {
    std::optional<std::string_view> line;
    do {
        line = lines_.next();
        if (!line) return false;
    } while (trim(*line).empty());
    row.line = lines_.line_number();

    split_fields(*line, fields_);
    const std::size_t coordinate_count = 2 * static_cast<std::size_t>(dimension_);
    if (fields_.size() != 2 + coordinate_count) {
        fail(row.line,
             "expected " + std::to_string(2 + coordinate_count) + " fields, found " + std::to_string(fields_.size()));
    }
    const auto* names = dimension_ == 2 ? coordinate_names_2d : coordinate_names_3d;
    try {
        row.frame = parse_unsigned(fields_[0], "frame");
        row.id = parse_unsigned(fields_[1], "id");
        for (std::size_t c = 0; c < coordinate_count; ++c)
            row.coordinates[c] = parse_finite_double(fields_[2 + c], names[c]);
    } catch (const std::invalid_argument& problem) {
        fail(row.line, problem.what());
    }
    const auto dim = static_cast<std::size_t>(dimension_);
    for (std::size_t k = 0; k < dim; ++k) {
        if (row.coordinates[k] > row.coordinates[dim + k]) {
            fail(row.line, fmt::format("{} {} is greater than {} {}", names[k], trim(fields_[2 + k]), names[dim + k],
                                       trim(fields_[2 + dim + k])));
        }
    }
    return true;
}

template <int Dim>
bool SceneReader::read_frame(SceneFrame<Dim>& frame) {
    if (Dim != dimension_) throw std::logic_error("SceneReader::read_frame: dimension differs from the header's");
    frame.clear();
    if (!has_pending_ && !read_row(pending_)) return false;
    has_pending_ = false;
    // The row that ended the previous frame had a larger number, so frames only grow here.
    frame.number = pending_.frame;

    Row& row = pending_;
    do {
        if (row.frame != frame.number) {
            if (row.frame < frame.number) {
                fail(row.line, fmt::format("frame {} comes after frame {}: frames must not "
                                           "decrease",
                                           row.frame, frame.number));
            }
            has_pending_ = true;
            break;
        }
        Box<double, Dim> box;
        for (int k = 0; k < Dim; ++k) {
            box.min[k] = row.coordinates[static_cast<std::size_t>(k)];
            box.max[k] = row.coordinates[static_cast<std::size_t>(Dim + k)];
        }
        frame.ids.push_back(row.id);
        frame.boxes.push_back(box);
        frame.lines.push_back(row.line);
    } while (read_row(row));

    sort_and_check_ids(frame);
    return true;
}

template <int Dim>
void SceneReader::sort_and_check_ids(SceneFrame<Dim>& frame) const {
    const auto& ids = frame.ids;
    if (std::adjacent_find(ids.begin(), ids.end(), std::greater_equal<>()) == ids.end()) return;

    std::vector<std::size_t> order(ids.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    // Stable, so that of two rows with one id the first stays first and the second is blamed.
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
    for (std::size_t i = 1; i < order.size(); ++i) {
        if (ids[order[i]] == ids[order[i - 1]]) {
            fail(frame.lines[order[i]], fmt::format("id {} appears twice in frame {} (first on line {})", ids[order[i]],
                                                    frame.number, frame.lines[order[i - 1]]));
        }
    }
    SceneFrame<Dim> sorted;
    sorted.number = frame.number;
    sorted.ids.reserve(order.size());
    sorted.boxes.reserve(order.size());
    sorted.lines.reserve(order.size());
    for (const std::size_t i : order) {
        sorted.ids.push_back(frame.ids[i]);
        sorted.boxes.push_back(frame.boxes[i]);
        sorted.lines.push_back(frame.lines[i]);
    }
    frame = std::move(sorted);
}

template bool SceneReader::read_frame<2>(SceneFrame<2>&);
template bool SceneReader::read_frame<3>(SceneFrame<3>&);

SceneWriter::SceneWriter(std::ostream& out, int dimension) : out_(out), dimension_(dimension) {
    if (dimension != 2 && dimension != 3) throw std::invalid_argument("scene dimension must be 2 or 3");
    buffer_.append(scene_header(dimension));
    buffer_ += '\n';
}

SceneWriter::~SceneWriter() {
    try {
        flush();
    } catch (...) {
        // A destructor must not throw; callers who care about errors call flush() themselves.
    }
}

template <int Dim>
void SceneWriter::write_frame(std::uint64_t frame, std::span<const BoxId> ids,
                              std::span<const Box<double, Dim>> boxes) {
    if (Dim != dimension_) throw std::logic_error("SceneWriter: dimension differs from the header's");
    if (ids.size() != boxes.size()) throw std::invalid_argument("SceneWriter: ids and boxes differ in length");
    auto out = std::back_inserter(buffer_);
    for (std::size_t i = 0; i < ids.size(); ++i) {
        // fmt's "{}" prints the shortest decimal that reads back to the same double.
        if constexpr (Dim == 2) {
            fmt::format_to(out, "{},{},{},{},{},{}\n", frame, ids[i], boxes[i].min[0], boxes[i].min[1], boxes[i].max[0],
                           boxes[i].max[1]);
        } else {
            fmt::format_to(out, "{},{},{},{},{},{},{},{}\n", frame, ids[i], boxes[i].min[0], boxes[i].min[1],
                           boxes[i].min[2], boxes[i].max[0], boxes[i].max[1], boxes[i].max[2]);
        }
        if (buffer_.size() >= csv_flush_threshold) flush();
    }
}

template void SceneWriter::write_frame<2>(std::uint64_t, std::span<const BoxId>, std::span<const Box<double, 2>>);
template void SceneWriter::write_frame<3>(std::uint64_t, std::span<const BoxId>, std::span<const Box<double, 3>>);

void SceneWriter::flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
    if (!out_) throw std::runtime_error("writing the scene failed");
}

}  // namespace smb::io
