#include "solver/manifold_order.h"

#include <algorithm>
#include <cstring>

namespace cyclone::detail {
namespace {

constexpr int kDigits = 8;     // bytes of a height's bits, least significant first
constexpr int kBuckets = 256;

// A height's bits as an unsigned number that orders as the height does: -0 as +0, a
// negative height's bits all flipped, a positive one's sign bit set.
std::uint64_t orderedBits(real height) {
    const real canonical = height + real(0);  // -0 + 0 is +0
    std::uint64_t bits;
    std::memcpy(&bits, &canonical, sizeof bits);
    return bits >> 63 ? ~bits : bits | (std::uint64_t(1) << 63);
}

int digit(std::uint64_t bits, int d) { return static_cast<int>((bits >> (8 * d)) & (kBuckets - 1)); }

}  // namespace

void sortByHeight(std::vector<ManifoldKey> &keys, std::vector<ManifoldKey> &scratch) {
    static_assert(sizeof(real) == sizeof(std::uint64_t), "heights are sorted by their 64 bits");
    const std::size_t n = keys.size();
    if (n < 2) return;
    std::uint32_t count[kDigits][kBuckets] = {};
    for (const ManifoldKey &k : keys) {
        const std::uint64_t bits = orderedBits(k.height);
        for (int d = 0; d < kDigits; ++d) ++count[d][digit(bits, d)];
    }
    scratch.resize(n);
    ManifoldKey *from = keys.data();
    ManifoldKey *to = scratch.data();
    const std::uint64_t firstBits = orderedBits(keys[0].height);
    for (int d = 0; d < kDigits; ++d) {
        if (count[d][digit(firstBits, d)] == n) continue;  // one value of this digit: nothing moves
        std::uint32_t start[kBuckets];
        std::uint32_t total = 0;
        for (int b = 0; b < kBuckets; ++b) {
            start[b] = total;
            total += count[d][b];
        }
        for (std::size_t i = 0; i < n; ++i) to[start[digit(orderedBits(from[i].height), d)]++] = from[i];
        std::swap(from, to);
    }
    if (from != keys.data()) std::copy(from, from + n, keys.data());
}

}  // namespace cyclone::detail
