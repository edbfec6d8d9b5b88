// The slots of removed bodies, springs, joints and characters are reused, the last freed
// first, so that a handle's index stays small; the slot's generation tells a handle to a
// removed record from one to its successor.
#pragma once

#include <cstdint>
#include <vector>

namespace cyclone::detail {

/// The index of a slot of `records` for a new record: the last one freed in `free`, or
/// a default record appended when none is free. The slot keeps its generation.
template <class Record>
std::uint32_t takeSlot(std::vector<Record> &records, std::vector<std::uint32_t> &free) {
    if (free.empty()) {
        records.emplace_back();
        return static_cast<std::uint32_t>(records.size() - 1);
    }
    const std::uint32_t index = free.back();
    free.pop_back();
    return index;
}

/// Ends the record in slot `index` of `records`: not alive, its generation moved on (old
/// handles no longer name it), the slot listed in `free`.
template <class Record>
void freeSlot(std::vector<Record> &records, std::vector<std::uint32_t> &free, std::uint32_t index) {
    records[index].alive = false;
    ++records[index].generation;
    free.push_back(index);
}

}  // namespace cyclone::detail
