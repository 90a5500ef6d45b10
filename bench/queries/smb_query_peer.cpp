// SPDX-License-Identifier: MIT
#include "queries/query_peer.hpp"
#include "smb/box_index.hpp"

namespace smb::bench {
namespace {

template <int Dim>
class SmbQueryPeer final : public QueryPeer<Dim> {
public:
    std::string name() const override { return "smb BoxIndex"; }
    void build(std::span<const Box<float, Dim>> boxes) override { index_.build(boxes); }
    void query(const Box<float, Dim>& q, std::vector<BoxId>& out) override { index_.query(q, out); }
    void cast(const Ray<float, Dim>& ray, RayHits mode, std::vector<RayHit<float>>& out) override {
        index_.cast_ray(ray, mode, out);
    }
    std::size_t bytes_held() const override { return index_.bytes_held(); }

private:
    BoxIndex<float, Dim> index_;
};

}  // namespace

std::unique_ptr<QueryPeer<2>> make_smb_query_peer_2d() { return std::make_unique<SmbQueryPeer<2>>(); }
std::unique_ptr<QueryPeer<3>> make_smb_query_peer_3d() { return std::make_unique<SmbQueryPeer<3>>(); }

}  // namespace smb::bench
