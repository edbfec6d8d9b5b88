// The order in which the solver takes a step's manifolds: lowest contact first.
#pragma once

#include <cstdint>
#include <vector>

#include "cyclone/core.h"

namespace cyclone {

/// A manifold on its way to the solver: its solve-order key and where it comes from.
struct ManifoldKey {
    real height = 0;          ///< Contact height, m along -gravity: lower contacts are solved first.
    std::uint32_t listed = 0; ///< Position in the pair walk: equal heights keep this order.
    std::uint32_t source = 0; ///< Pair index << 2 | manifold, as in World::Impl::solverSource.
};

namespace detail {

/// Sorts `keys`, listed in the order of their `listed` fields, by height, equal heights
/// in that order: what sorting by (height, listed) gives. A stable radix sort on the
/// heights' bits, through `scratch`, with no comparison to mispredict.
void sortByHeight(std::vector<ManifoldKey> &keys, std::vector<ManifoldKey> &scratch);

}  // namespace detail
}  // namespace cyclone
