// SPDX-License-Identifier: MIT
// A consumer of smb: two boxes that share a face must be reported as one overlapping pair, by a
// World (under ids), by a Detector (over an array, by index; with and without a skin) and by
// find_overlapping_pairs over a std::vector.

#include <smb/smb.hpp>

#include <iostream>
#include <vector>

int main() {
    smb::World3d world;
    world.insert(10, smb::Box3d{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}});
    world.insert(20, smb::Box3d{{1.0, 0.0, 0.0}, {2.0, 1.0, 1.0}});
    std::vector<smb::Pair> pairs;
    world.detect(pairs);
    if (pairs.size() != 1 || pairs[0].a != 10 || pairs[0].b != 20) {
        std::cerr << "expected the single pair (10, 20), got " << pairs.size() << " pairs\n";
        return 1;
    }
    const std::vector<smb::Box3d> array{smb::Box3d{{5, 5, 5}, {6, 6, 6}}, smb::Box3d{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}},
                                        smb::Box3d{{1.0, 0.0, 0.0}, {2.0, 1.0, 1.0}}};
    smb::Detector3d detector;
    detector.detect(array, pairs);
    if (pairs.size() != 1 || pairs[0].a != 1 || pairs[0].b != 2) {
        std::cerr << "expected the single pair of indices (1, 2), got " << pairs.size() << " pairs\n";
        return 1;
    }
    smb::DetectorSettings skinned;  // a Detector's own settings: the shared ones and a skin
    skinned.skin = 0.1;
    smb::Detector3d with_skin(skinned);
    with_skin.detect(array, pairs);
    const std::vector<smb::Pair> once = smb::find_overlapping_pairs(array);  // the vector as it is
    if (pairs != once || once.size() != 1) {
        std::cerr << "expected the single pair of indices (1, 2) with a skin and from find_overlapping_pairs\n";
        return 1;
    }
    std::cout << "smb " << SMB_VERSION_STRING << ": pair (10, 20) found, and indices (1, 2)\n";
    return 0;
}
