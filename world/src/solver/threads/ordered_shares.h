// A Gauss-Seidel pass on two threads that gives the numbers of one.
//
// Design note. Two of the solver's passes run in one order that the velocity passes'
// split (threads/partition.h) would change, and with it their numbers: the rolling and
// spinning resistance rows and the carrier pass's first pass, over the manifolds without
// a carrier. Each entry of such a pass (a row, a manifold) reads and writes its own two
// bodies and nothing else. So each thread takes the entries whose first moving body lies
// in its half of the partition, in the pass's order, and before an entry waits until the
// other thread has finished the last earlier entry that touches either of its bodies.
// Every body then meets its entries one after another in the pass's order, and every
// entry finds the velocities one thread would have left it: the numbers do not depend on
// the thread count. The waits come near the seam, where the halves meet. The immovable
// world (solver body 0) is read by both threads and written by neither.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/threads/pass_flags.h"

namespace cyclone::detail {

/// Passes of fewer entries stay on one thread: their hand-over would cost more than half
/// of them.
inline constexpr std::size_t kMinSharedEntries = 128;

struct OrderedShares {
    std::vector<int> share[2];  ///< Each thread's entries, in the pass's order.
    /// Per entry, two places: the other thread's entries it waits for (-1: none).
    std::vector<int> waits;
    PassFlags finished;  ///< Per entry: whether it is solved in this pass.
    std::vector<int> lastEntry;          ///< Scratch per solver body: the last entry met that touches it.
    std::vector<signed char> lastShare;  ///< Scratch per solver body: that entry's thread.
};

/// Splits `count` entries of a pass, entry k touching solver bodies bodyA(k) and
/// bodyB(k), between two threads by `side` (per solver body, 0 or 1: the partition's
/// halves; -1 for body 0), and lists what each waits for. `bodyCount` counts the solver
/// bodies.
template <class BodyA, class BodyB>
void buildOrderedShares(std::size_t count, const BodyA &bodyA, const BodyB &bodyB, const std::vector<signed char> &side,
                        int bodyCount, OrderedShares &shares) {
    shares.share[0].clear();
    shares.share[1].clear();
    shares.waits.resize(2 * count);
    shares.lastEntry.assign(static_cast<std::size_t>(bodyCount), -1);
    shares.lastShare.resize(static_cast<std::size_t>(bodyCount));
    for (std::size_t k = 0; k < count; ++k) {
        const int bodies[2] = {bodyA(k), bodyB(k)};
        const int first = side[bodies[0]] >= 0 ? side[bodies[0]] : side[bodies[1]];
        const signed char mine = static_cast<signed char>(first > 0 ? 1 : 0);
        shares.share[mine].push_back(static_cast<int>(k));
        for (int j = 0; j < 2; ++j) {
            const int body = bodies[j];
            int &wait = shares.waits[2 * k + j];
            wait = -1;
            if (body == 0) continue;
            if (shares.lastEntry[body] >= 0 && shares.lastShare[body] != mine) wait = shares.lastEntry[body];
            shares.lastEntry[body] = static_cast<int>(k);
            shares.lastShare[body] = mine;
        }
    }
    shares.finished.reserve(count);
}

/// Solves share `share`'s entries in order with solve(k), each once the other thread's
/// entries it waits for are solved.
template <class Solve>
void solveOrderedShare(OrderedShares &shares, int share, const Solve &solve) {
    for (const int k : shares.share[share]) {
        for (int j = 0; j < 2; ++j) {
            const int wait = shares.waits[2 * static_cast<std::size_t>(k) + j];
            if (wait >= 0) shares.finished.await(static_cast<std::size_t>(wait));
        }
        solve(k);
        shares.finished.finish(static_cast<std::size_t>(k));
    }
}

}  // namespace cyclone::detail
