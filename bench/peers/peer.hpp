// SPDX-License-Identifier: MIT
#pragma once
// One interface for every broad phase in the comparison. The harness feeds each method the same
// scene steps and compares the pairs it returns; whatever a method does to turn its own output
// into exact, unique, closed-overlap pairs of ids is part of its measured time.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "scenes/scene.hpp"
#include "smb/pair.hpp"

namespace smb::bench {

template <int Dim>
class Peer {
public:
    virtual ~Peer() = default;

    /// Called before build() and step(), outside the timing and the heap count: only for work a
    /// user of the method would not do, such as copying the common float boxes into the
    /// method's own input type.
    virtual void prepare(const SceneStep<Dim>& /*step*/) {}

    /// Step 0: every box of `step` is new. Fills `pairs` (cleared first) with every overlapping
    /// pair, each once, a < b, in any order.
    virtual void build(const SceneStep<Dim>& step, std::vector<Pair>& pairs) = 0;

    /// A later step: boxes in step.removed_ids are gone, those before step.first_inserted moved,
    /// the rest are new. Same output contract as build().
    virtual void step(const SceneStep<Dim>& step, std::vector<Pair>& pairs) = 0;

    /// Method-specific facts for the report, as JSON members ("key":value,...), or empty.
    [[nodiscard]] virtual std::string details_json() const { return {}; }
};

/// A method that keeps nothing between steps: it only sees the complete box set.
template <int Dim>
class StatelessPeer : public Peer<Dim> {
public:
    void build(const SceneStep<Dim>& step, std::vector<Pair>& pairs) final { find_pairs(step, pairs); }
    void step(const SceneStep<Dim>& step, std::vector<Pair>& pairs) final { find_pairs(step, pairs); }

protected:
    virtual void find_pairs(const SceneStep<Dim>& step, std::vector<Pair>& pairs) = 0;
};

[[nodiscard]] inline Pair ordered_pair(BoxId first, BoxId second) noexcept {
    return first < second ? Pair{first, second} : Pair{second, first};
}

/// Every method name this build knows, with the dimensions it runs in.
struct PeerInfo {
    std::string name;
    bool runs_2d = false;
    bool runs_3d = false;
};
[[nodiscard]] std::vector<PeerInfo> available_peers();

/// The named method for Dim, or nullptr when this build lacks it or it has no Dim version.
template <int Dim>
[[nodiscard]] std::unique_ptr<Peer<Dim>> make_peer(std::string_view name);

}  // namespace smb::bench
