// A consumer of smb: two boxes that share a face must be reported as one overlapping pair.

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
    std::cout << "smb " << SMB_VERSION_STRING << ": pair (10, 20) found\n";
    return 0;
}
