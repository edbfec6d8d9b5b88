#include "solver_partition.h"

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

void partitionManifolds(const std::vector<SolverManifold> &manifolds, const std::vector<int> &solveOrder,
                        const std::vector<Vector3> &positions, PartitionScratch &scratch, SolverPartition &partition) {
    const int n = static_cast<int>(solveOrder.size());
    std::vector<int>(&order)[3] = partition.order;
    for (std::vector<int> &part : order) part.clear();
    partition.split = n >= kMinSplitManifolds && positions.size() > 2;
    if (!partition.split) {
        order[0] = solveOrder;
    } else {
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
        for (int i : solveOrder) {
            const int a = side[manifolds[i].a];
            const int b = side[manifolds[i].b];
            const int part = a < 0 ? b : b < 0 ? a : a == b ? a : SolverPartition::kSeam;
            order[std::max(part, 0)].push_back(i);
        }
    }
    for (int part = 0; part < 3; ++part) buildSchedule(manifolds, order[part], partition.groups[part], scratch.schedule);
}

}  // namespace cyclone::detail
