// The order in which the solver takes a step's manifolds: lowest contact first.
#pragma once

#include <cstdint>
#include <vector>

#include "contacts/pair_cache.h"
#include "cyclone/core.h"

namespace cyclone {

/// A manifold on its way to the solver: its solve-order key and where it comes from.
/// The keys are listed in the order of the pair walk, which equal heights keep.
struct ManifoldKey {
    real height = 0;          ///< Contact height, m along -gravity: lower contacts are solved first.
    detail::ManifoldRef manifold;  ///< The pair manifold it comes from.
};

namespace detail {

/// Sorts `keys` by height, equal heights in the order they are listed: a stable radix
/// sort on the heights' bits, through `scratch`, with no comparison to mispredict.
void sortByHeight(std::vector<ManifoldKey> &keys, std::vector<ManifoldKey> &scratch);

}  // namespace detail
}  // namespace cyclone
