// Union-find over a parent array, each entry its own root to start: the islands' bodies
// joined by contacts, springs and joints (islands.cpp), and the landing correction's
// bodies joined by joints (contacts/landing.cpp).
#pragma once

#include <algorithm>
#include <vector>

namespace cyclone::detail {

/// The root of i's set, halving the path on the way.
inline int findRoot(std::vector<int> &parent, int i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

/// Joins the sets of x and y. The smaller root becomes the root of both, so a root never
/// comes after a member of its set (islands.cpp numbers its islands in one walk on that).
inline void uniteSets(std::vector<int> &parent, int x, int y) {
    x = findRoot(parent, x);
    y = findRoot(parent, y);
    if (x != y) parent[std::max(x, y)] = std::min(x, y);
}

}  // namespace cyclone::detail
