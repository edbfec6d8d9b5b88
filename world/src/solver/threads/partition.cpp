#include "solver/threads/partition.h"

#include <algorithm>
#include <limits>

namespace cyclone::detail {
namespace {

// The axis along which the bodies spread most (0, 1 or 2).
int widestAxis(const std::vector<Vector3> &positions) {
    Vector3 low = Vector3::Constant(std::numeric_limits<real>::infinity());
    Vector3 high = -low;
    for (std::size_t k = 1; k < positions.size(); ++k) {
        low = low.cwiseMin(positions[k]);
        high = high.cwiseMax(positions[k]);
    }
    int axis = 0;
    (high - low).maxCoeff(&axis);
    return axis;
}

}  // namespace

void partitionManifolds(const SolverManifolds &manifolds, const std::vector<real> &heights,
                        const std::vector<int> &solveOrder, const std::vector<Vector3> &positions, bool twoThreads,
                        PartitionScratch &scratch, SolverPartition &partition) {
    const int n = static_cast<int>(solveOrder.size());
    std::vector<int>(&order)[3] = partition.order;
    for (int part = 0; part < 3; ++part) {
        order[part].clear();
        partition.groups[part].clear();
    }
    partition.split = n >= kMinSplitManifolds && positions.size() > 2;
    if (!partition.split) {
        order[0] = solveOrder;
        buildLevelSchedule(manifolds, heights, order[0], partition.groups[0], scratch.schedule);
        return;
    }
    const int axis = widestAxis(positions);
    std::vector<real> &places = scratch.places;
    places.clear();
    for (std::size_t k = 1; k < positions.size(); ++k) places.push_back(positions[k][axis]);
    const auto middle = places.begin() + static_cast<std::ptrdiff_t>(places.size() / 2);
    std::nth_element(places.begin(), middle, places.end());
    const real median = *middle;
    std::vector<signed char> &side = scratch.side;
    side.resize(positions.size());
    side[0] = -1;  // immovable: joins either half
    for (std::size_t k = 1; k < positions.size(); ++k) side[k] = positions[k][axis] < median ? 0 : 1;
    const auto partOf = [&](int i) {
        const int a = side[manifolds[i].a];
        const int b = side[manifolds[i].b];
        return std::max(a < 0 ? b : b < 0 ? a : a == b ? a : SolverPartition::kSeam, 0);
    };
    // Both halves in one list: their manifolds share no moving body, so any order that
    // keeps each half's gives the same numbers. Its order, not the thread count, decides
    // each half's.
    std::vector<int> &halves = scratch.halves;
    halves.clear();
    for (int i : solveOrder) (partOf(i) == SolverPartition::kSeam ? order[SolverPartition::kSeam] : halves).push_back(i);
    buildLevelSchedule(manifolds, heights, halves, partition.groups[0], scratch.schedule);
    buildLevelSchedule(manifolds, heights, order[SolverPartition::kSeam], partition.groups[SolverPartition::kSeam],
                       scratch.schedule);
    for (int i : halves) order[partOf(i)].push_back(i);
    if (!twoThreads) return;  // one thread solves both halves' groups as one list
    for (int half = 0; half < 2; ++half) buildSchedule(manifolds, order[half], partition.groups[half], scratch.schedule);
}

}  // namespace cyclone::detail
