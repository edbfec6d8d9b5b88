// Room for a list's next items, grown by an eighth.
//
// Design note. The lists a step fills (rows, points, impulses) keep the room of their
// longest step, so that a steady step allocates nothing. std::vector doubles its room
// when it is short, which left up to half of each list's room unused at a landing pile's
// peak; growing by an eighth leaves at most an eighth, for a few more (cheap) copies while
// the lists grow.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace cyclone::detail {

/// Gives `list` room for `more` items past its size: at least an eighth more than it had
/// when it is short.
template <class T>
void makeRoom(std::vector<T> &list, std::size_t more = 1) {
    const std::size_t needed = list.size() + more;
    if (needed <= list.capacity()) return;
    list.reserve(std::max(needed, list.capacity() + list.capacity() / 8 + 16));
}

}  // namespace cyclone::detail
