// Room for a list's next items, grown by an eighth.
//
// Design note. The lists a step fills (rows, points, impulses) keep the room of their
// longest step, so that a steady step allocates nothing. std::vector doubles its room
// when it is short, which leaves up to half of each list's room unused at a landing pile's
// peak; growing by an eighth leaves at most an eighth, for a few more (cheap) copies while
// the lists grow.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace cyclone::detail {

/// Gives `list` room for `more` items past its size: at least an eighth more than it had
/// when it is short. An empty list lets its old room go before it takes the new: a
/// step's lists grow together in the step that holds the most, and each holding its old
/// room and its new at once made the heap's peak.
template <class T>
void makeRoom(std::vector<T> &list, std::size_t more = 1) {
    const std::size_t needed = list.size() + more;
    if (needed <= list.capacity()) return;
    const std::size_t room = std::max(needed, list.capacity() + list.capacity() / 8 + 16);
    if (list.empty()) std::vector<T>().swap(list);
    list.reserve(room);
}

/// Resizes `list` to `count` items whose every value is written again before it is read:
/// when it grows, its old room goes before the new is taken (the values are not kept),
/// with room for an eighth more.
template <class T>
void resizeAnew(std::vector<T> &list, std::size_t count) {
    if (count > list.capacity()) {
        list.clear();
        makeRoom(list, count);
    }
    list.resize(count);
}

}  // namespace cyclone::detail
