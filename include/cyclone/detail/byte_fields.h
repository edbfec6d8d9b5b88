/// \file
/// Fixed-size fields at byte offsets of a buffer, in the machine's byte order: the headers
/// of a saved World state and of a saved run (not part of the API).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace cyclone::detail {

/// Writes `value` at byte `at` of `out`, which holds at least at + sizeof(T) bytes.
template <class T>
void put(std::vector<std::uint8_t> &out, std::size_t at, T value) {
    std::memcpy(out.data() + at, &value, sizeof value);
}

/// The T at byte `at` of `in`, which holds at least at + sizeof(T) bytes.
template <class T>
T take(const std::vector<std::uint8_t> &in, std::size_t at) {
    T value;
    std::memcpy(&value, in.data() + at, sizeof value);
    return value;
}

}  // namespace cyclone::detail
