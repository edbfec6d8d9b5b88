#include "solver/threads/ordered_shares.h"

namespace cyclone::detail {

void beginOrderedPass(OrderedShares &shares) {
    if (++shares.pass == 0) {  // wrapped: no entry may look solved in this pass
        for (std::size_t k = 0; k < shares.capacity; ++k) shares.done[k].store(0, std::memory_order_relaxed);
        shares.pass = 1;
    }
}

}  // namespace cyclone::detail
