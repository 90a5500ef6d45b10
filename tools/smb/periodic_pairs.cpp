// SPDX-License-Identifier: MIT
#include "periodic_pairs.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <iterator>
#include <stdexcept>
#include <string_view>

#include "csv_fields.hpp"
#include "scene_follower.hpp"
#include "smb/periodic.hpp"
#include "smb/world.hpp"

namespace smb::cli {

namespace {

/// A bound as a scene writes a coordinate: a decimal number (subnormals included), with no
/// sign but '-'; hex, infinities and NaN are refused.
double parse_bound(std::string_view text, std::string_view axis) {
    const std::string_view bound = io::trim(text);
    const std::string column = fmt::format("{} bound", axis);
    if (bound.starts_with('+'))
        throw std::invalid_argument(fmt::format("{} {} has a '+': write it without a sign", column, io::quoted(bound)));
    return io::parse_finite_double(bound, column);
}

constexpr std::size_t kFlushAt = std::size_t{1} << 20;

template <int Dim>
void write_frames(io::SceneReader& reader, std::ostream& out, const PeriodicAxes& axes) {
    PeriodicDomain<double, Dim> domain;
    for (int k = 0; k < Dim; ++k) {
        if (axes[static_cast<std::size_t>(k)]) domain.wrap(k, axes[k]->first, axes[k]->second);
    }
    World<double, Dim> world;
    std::vector<PeriodicPair> pairs;
    io::SceneFollower<Dim> scene(reader);
    std::string buffer = Dim == 2 ? "frame,a,b,sx,sy\n" : "frame,a,b,sx,sy,sz\n";
    auto flush = [&] {
        out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        buffer.clear();
        if (!out) throw std::runtime_error("writing the pairs failed");
    };
    while (scene.advance(world)) {
        const std::uint64_t number = scene.frame_number();
        try {
            world.detect(domain, pairs);
        } catch (const Error& error) {
            throw std::runtime_error(fmt::format("frame {}: {}", number, error.what()));
        }
        sort_periodic_pairs(pairs);
        auto text = std::back_inserter(buffer);
        for (const PeriodicPair& p : pairs) {
            if constexpr (Dim == 2)
                fmt::format_to(text, "{},{},{},{},{}\n", number, p.a, p.b, p.shift[0], p.shift[1]);
            else
                fmt::format_to(text, "{},{},{},{},{},{}\n", number, p.a, p.b, p.shift[0], p.shift[1], p.shift[2]);
            if (buffer.size() >= kFlushAt) flush();
        }
    }
    flush();
}

}  // namespace

PeriodicAxes parse_periodic_axes(const std::string& text) {
    PeriodicAxes axes;
    std::string_view rest = text;
    while (true) {
        const std::size_t comma = rest.find(',');
        const std::string_view field = io::trim(rest.substr(0, comma));
        const std::string axis(1, "xyzw"[std::min<std::size_t>(axes.size(), 3)]);
        if (field == "-") {
            axes.emplace_back();
        } else {
            const std::size_t colon = field.find(':');
            if (colon == std::string_view::npos)
                throw std::invalid_argument(
                    fmt::format("the {} axis {} is neither LO:HI nor '-'", axis, io::quoted(field)));
            const double lo = parse_bound(field.substr(0, colon), axis);
            const double hi = parse_bound(field.substr(colon + 1), axis);
            if (!(lo < hi))
                throw std::invalid_argument(
                    fmt::format("the {} interval {}:{} is empty (LO must be below HI)", axis, lo, hi));
            if (!std::isfinite(hi - lo))
                throw std::invalid_argument(fmt::format(
                    "the {} interval {}:{} is too wide: its period HI - LO overflows a double", axis, lo, hi));
            axes.emplace_back(std::pair{lo, hi});
        }
        if (comma == std::string_view::npos) break;
        rest = rest.substr(comma + 1);
    }
    if (axes.size() != 2 && axes.size() != 3)
        throw std::invalid_argument(fmt::format("expected 2 or 3 axes (X0:X1,Y0:Y1[,Z0:Z1]), found {}", axes.size()));
    return axes;
}

void write_periodic_pairs(io::SceneReader& reader, std::ostream& out, const PeriodicAxes& axes) {
    if (static_cast<int>(axes.size()) != reader.dimension())
        throw CLI::ValidationError("--periodic",
                                   fmt::format("names {} axes but the scene is {}D", axes.size(), reader.dimension()));
    if (reader.dimension() == 2)
        write_frames<2>(reader, out, axes);
    else
        write_frames<3>(reader, out, axes);
}

}  // namespace smb::cli
