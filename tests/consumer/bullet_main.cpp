// SPDX-License-Identifier: MIT
// A consumer of smb::bullet: two proxies that share a face must be one pair in Bullet's cache.

#include <smb/bullet/broadphase.hpp>

#include <iostream>

int main() {
    smb::bullet::Broadphase broadphase;
    broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), BOX_SHAPE_PROXYTYPE, nullptr, 1, -1, nullptr);
    broadphase.createProxy(btVector3(1, 0, 0), btVector3(2, 1, 1), BOX_SHAPE_PROXYTYPE, nullptr, 1, -1, nullptr);
    broadphase.calculateOverlappingPairs(nullptr);
    if (broadphase.getOverlappingPairCache()->getNumOverlappingPairs() != 1) {
        std::cerr << "expected one pair in Bullet's cache\n";
        return 1;
    }
    std::cout << "smb::bullet: one pair in Bullet's cache\n";
    return 0;
}
