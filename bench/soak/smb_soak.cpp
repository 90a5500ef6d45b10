// SPDX-License-Identifier: MIT
// smb_soak: a long run of one World under heavy churn, for the soak and scale figures of
// docs/robustness.md.
//
// Every step moves every box a little, removes a fixed fraction of the boxes and inserts as
// many fresh ones (new ids), then detects. At sampled steps the pairs are compared with
// workload::grid_pairs, a uniform grid that shares no code with the SMB pipeline, and the
// memory the world holds (bytes_held) and the process's resident memory are printed. One CSV
// row per sample goes to standard output, flushed at once, so an interrupted run keeps its
// figures. Exit status: 0 all checks exact, 2 a check differed, 1 bad arguments.
//
//   smb_soak [--dim 2|3] [--boxes N] [--steps S] [--churn F] [--sample-every K]
//            [--check-every K] [--density E] [--motion L] [--seed S]
//
// --check-every 0 skips the exact comparison (the scale run); samples are still printed.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "process_memory.hpp"
#include "smb/workload/dynamic_environment.hpp"
#include "smb/workload/reference_grid.hpp"
#include "smb/world.hpp"

namespace {

using smb::soak::peak_resident_bytes;
using smb::soak::resident_bytes;

struct SoakOptions {
    int dim = 3;
    std::size_t boxes = 100000;
    std::size_t steps = 10000;
    double churn = 0.2;              ///< fraction of the boxes removed and inserted every step
    std::size_t sample_every = 100;  ///< print a row every this many steps (and at 0 and the end)
    std::size_t check_every = 100;   ///< compare with the grid every this many steps; 0 never
    double density = 0.4;            ///< packing density E of the paper's environment
    double motion = 1e-3;            ///< largest move per step, as a fraction of the cube side
    std::uint64_t seed = 1;
};

SoakOptions parse_options(int argc, char** argv) {
    SoakOptions options;
    for (int i = 1; i < argc; ++i) {
        const std::string name = argv[i];
        if (i + 1 >= argc) throw std::invalid_argument("option " + name + " needs a value");
        const std::string value = argv[++i];
        if (name == "--dim") {
            options.dim = std::stoi(value);
        } else if (name == "--boxes") {
            options.boxes = std::stoull(value);
        } else if (name == "--steps") {
            options.steps = std::stoull(value);
        } else if (name == "--churn") {
            options.churn = std::stod(value);
        } else if (name == "--sample-every") {
            options.sample_every = std::stoull(value);
        } else if (name == "--check-every") {
            options.check_every = std::stoull(value);
        } else if (name == "--density") {
            options.density = std::stod(value);
        } else if (name == "--motion") {
            options.motion = std::stod(value);
        } else if (name == "--seed") {
            options.seed = std::stoull(value);
        } else {
            throw std::invalid_argument("unknown option " + name);
        }
    }
    if (options.dim != 2 && options.dim != 3) throw std::invalid_argument("--dim is 2 or 3");
    if (options.boxes == 0) throw std::invalid_argument("--boxes must be positive");
    if (!(options.churn >= 0 && options.churn <= 1)) throw std::invalid_argument("--churn in [0, 1]");
    if (options.sample_every == 0) throw std::invalid_argument("--sample-every must be positive");
    return options;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The boxes of the run: the paper's sizes (sides in [0.4, 1], H = 2.5) in a cube of the
/// requested density, with churn on top of the motion.
template <int Dim>
class ChurningScene {
public:
    using BoxT = smb::Box<double, Dim>;

    explicit ChurningScene(const SoakOptions& options)
        : options_(options),
          side_(smb::workload::cube_side_for_density(options.boxes, options.density, kMinSide, kMaxSide, Dim)),
          random_(options.seed) {
        ids_.resize(options.boxes);
        boxes_.resize(options.boxes);
        for (std::size_t i = 0; i < options.boxes; ++i) {
            ids_[i] = next_id_++;
            boxes_[i] = random_box();
        }
        order_.resize(options.boxes);
    }

    /// Moves every box, then replaces `churn` of them by fresh ones; fills the three lists.
    void step() {
        std::uniform_real_distribution<double> move(-options_.motion * side_, options_.motion * side_);
        for (BoxT& box : boxes_) {
            for (int k = 0; k < Dim; ++k) {
                const double extent = box.max[k] - box.min[k];
                const double low = std::clamp(box.min[k] + move(random_), 0.0, side_ - extent);
                box.min[k] = low;
                box.max[k] = low + extent;
            }
        }
        const auto replaced = static_cast<std::size_t>(std::llround(options_.churn * double(ids_.size())));
        std::iota(order_.begin(), order_.end(), std::size_t{0});
        for (std::size_t i = 0; i < replaced; ++i) {
            std::uniform_int_distribution<std::size_t> pick(i, order_.size() - 1);
            std::swap(order_[i], order_[pick(random_)]);
        }
        std::sort(order_.begin(), order_.begin() + static_cast<std::ptrdiff_t>(replaced));
        removed_ids_.clear();
        inserted_ids_.clear();
        inserted_boxes_.clear();
        std::vector<std::uint8_t> is_replaced(ids_.size(), 0);
        for (std::size_t i = 0; i < replaced; ++i) {
            const std::size_t slot = order_[i];
            is_replaced[slot] = 1;
            removed_ids_.push_back(ids_[slot]);
            ids_[slot] = next_id_++;
            boxes_[slot] = random_box();
            inserted_ids_.push_back(ids_[slot]);
            inserted_boxes_.push_back(boxes_[slot]);
        }
        updated_ids_.clear();
        updated_boxes_.clear();
        for (std::size_t slot = 0; slot < ids_.size(); ++slot) {
            if (is_replaced[slot] != 0) continue;
            updated_ids_.push_back(ids_[slot]);
            updated_boxes_.push_back(boxes_[slot]);
        }
    }

    void apply_step_to(smb::World<double, Dim>& world) const {
        world.remove(removed_ids_);
        world.update(updated_ids_, updated_boxes_);
        world.insert(inserted_ids_, inserted_boxes_);
    }

    [[nodiscard]] const std::vector<smb::BoxId>& ids() const { return ids_; }
    [[nodiscard]] const std::vector<BoxT>& boxes() const { return boxes_; }
    [[nodiscard]] double side() const { return side_; }

private:
    static constexpr double kMinSide = 0.4;
    static constexpr double kMaxSide = 1.0;

    BoxT random_box() {
        std::uniform_real_distribution<double> length(kMinSide, kMaxSide);
        BoxT box;
        for (int k = 0; k < Dim; ++k) {
            const double extent = length(random_);
            std::uniform_real_distribution<double> low(0.0, side_ - extent);
            box.min[k] = low(random_);
            box.max[k] = box.min[k] + extent;
        }
        return box;
    }

    SoakOptions options_;
    double side_;
    std::mt19937_64 random_;
    smb::BoxId next_id_ = 0;
    std::vector<smb::BoxId> ids_;
    std::vector<BoxT> boxes_;
    std::vector<std::size_t> order_;
    std::vector<smb::BoxId> removed_ids_;
    std::vector<smb::BoxId> updated_ids_;
    std::vector<BoxT> updated_boxes_;
    std::vector<smb::BoxId> inserted_ids_;
    std::vector<BoxT> inserted_boxes_;
};

/// Counts the pairs only one side has; prints the first few of each.
std::size_t count_differences(const std::vector<smb::Pair>& found, const std::vector<smb::Pair>& expected,
                              std::size_t step) {
    std::vector<smb::Pair> missing;
    std::vector<smb::Pair> extra;
    std::set_difference(expected.begin(), expected.end(), found.begin(), found.end(), std::back_inserter(missing));
    std::set_difference(found.begin(), found.end(), expected.begin(), expected.end(), std::back_inserter(extra));
    for (std::size_t i = 0; i < std::min<std::size_t>(missing.size(), 5); ++i)
        std::cerr << "step " << step << ": missing pair " << missing[i].a << ' ' << missing[i].b << '\n';
    for (std::size_t i = 0; i < std::min<std::size_t>(extra.size(), 5); ++i)
        std::cerr << "step " << step << ": extra pair " << extra[i].a << ' ' << extra[i].b << '\n';
    return missing.size() + extra.size();
}

template <int Dim>
int soak(const SoakOptions& options) {
    const auto setup_start = std::chrono::steady_clock::now();
    ChurningScene<Dim> scene(options);
    smb::World<double, Dim> world;
    world.insert(scene.ids(), scene.boxes());
    std::cout << "# dim " << Dim << ", boxes " << options.boxes << ", cube side " << scene.side() << ", churn "
              << options.churn << ", motion " << options.motion << ", seed " << options.seed << ", setup "
              << seconds_since(setup_start) << " s\n";
    std::cout << "step,boxes,pairs,step_s,detect_s,bytes_held,bytes_per_box,rss_bytes,"
                 "peak_rss_bytes,checked\n"
              << std::flush;

    std::vector<smb::Pair> pairs;
    std::size_t checks = 0;
    std::size_t failed_checks = 0;
    double detect_total = 0;
    double step_total = 0;
    for (std::size_t step = 0; step <= options.steps; ++step) {
        const auto step_start = std::chrono::steady_clock::now();
        if (step > 0) {
            scene.step();
            scene.apply_step_to(world);
        }
        const auto detect_start = std::chrono::steady_clock::now();
        world.detect(pairs);
        const double detect_s = seconds_since(detect_start);
        const double step_s = seconds_since(step_start);
        if (step > 0) {
            detect_total += detect_s;
            step_total += step_s;
        }

        const bool last = step == options.steps;
        std::string checked = "-";
        if (options.check_every != 0 && (step % options.check_every == 0 || last)) {
            smb::sort_pairs(pairs);
            const auto expected = smb::workload::grid_pairs<double, Dim>(scene.ids(), scene.boxes());
            const std::size_t differences = count_differences(pairs, expected, step);
            ++checks;
            if (differences != 0) ++failed_checks;
            checked = differences == 0 ? "exact" : std::to_string(differences) + " differ";
        }
        if (step % options.sample_every == 0 || last) {
            const std::size_t held = world.bytes_held();
            std::cout << step << ',' << world.size() << ',' << pairs.size() << ',' << step_s << ',' << detect_s << ','
                      << held << ',' << static_cast<double>(held) / static_cast<double>(world.size()) << ','
                      << resident_bytes() << ',' << peak_resident_bytes() << ',' << checked << '\n'
                      << std::flush;
        }
    }
    const double steps = static_cast<double>(std::max<std::size_t>(options.steps, 1));
    std::cout << "# mean step " << step_total / steps << " s, mean detect " << detect_total / steps << " s, checks "
              << checks << ", failed " << failed_checks << '\n';
    return failed_checks == 0 ? 0 : 2;
}

}  // namespace

int main(int argc, char** argv) {
    SoakOptions options;
    try {
        options = parse_options(argc, argv);
    } catch (const std::exception& error) {
        std::cerr << "smb_soak: " << error.what() << '\n';
        return 1;
    }
    return options.dim == 2 ? soak<2>(options) : soak<3>(options);
}
