#include "world/body_store.h"

#include <algorithm>

#include "world/validation.h"

namespace cyclone::detail {

BodyRecord &BodyStore::record(BodyId id, const char *function) {
    if (!contains(id))
        refuse(function, "id", "does not name a body of this world (index " + std::to_string(id.index) +
                                   ", generation " + std::to_string(id.generation) + ")");
    return records[id.index];
}

const BodyRecord &BodyStore::record(BodyId id, const char *function) const {
    return const_cast<BodyStore *>(this)->record(id, function);
}

BodyRecord &BodyStore::changeableRecord(BodyId id, const char *function) {
    BodyRecord &r = record(id, function);
    if (r.isolated)
        refuse(function, "id",
               "names a body isolated for a non-finite state (see StepStats::isolatedBodies), which is never "
               "simulated again; remove it and add a new one");
    return r;
}

BodyRecord &BodyStore::dynamicRecord(BodyId id, const char *function) {
    BodyRecord &r = changeableRecord(id, function);
    if (r.kinematic) refuse(function, "id", "names a kinematic body, which moves only at the velocity it is given");
    if (r.immovable) refuse(function, "id", "names a static body, which never moves");
    return r;
}

BodyRecord &BodyStore::movableRecord(BodyId id, const char *function) {
    BodyRecord &r = changeableRecord(id, function);
    if (r.immovable && !r.kinematic) refuse(function, "id", "names a static body, which never moves");
    return r;
}

void BodyStore::updateAwakeList(std::uint32_t index) {
    BodyRecord &r = records[index];
    const bool listed = r.alive && !r.immovable && !r.isolated && r.body.getAwake();
    if (listed == (r.awakeSlot >= 0)) return;
    if (listed) {
        if (!awake.empty() && records[awake.back()].rank > r.rank) awakeSorted = false;
        r.awakeSlot = static_cast<int>(awake.size());
        awake.push_back(index);
        return;
    }
    const std::uint32_t last = awake.back();
    awake[r.awakeSlot] = last;
    records[last].awakeSlot = r.awakeSlot;
    awake.pop_back();
    r.awakeSlot = -1;
    if (last != index) awakeSorted = false;
}

void BodyStore::sortAwake() {
    if (awakeSorted) return;
    std::sort(awake.begin(), awake.end(), [&](std::uint32_t x, std::uint32_t y) { return records[x].rank < records[y].rank; });
    for (std::size_t k = 0; k < awake.size(); ++k) records[awake[k]].awakeSlot = static_cast<int>(k);
    awakeSorted = true;
}

}  // namespace cyclone::detail
