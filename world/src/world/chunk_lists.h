// Lists that a job's chunks append to, one per thread, read back chunk by chunk.
//
// Design note. A step's tests run in chunks shared between the threads
// (Workers::forEachChunkOnThreads), and what they find is read afterwards in the chunks'
// order, so that results do not depend on which thread ran which chunk. A list per chunk
// would do, but each chunk's list keeps the room of the most that chunk ever found: on a
// landing pile, whose pairs move from chunk to chunk, that adds up to three times what
// any one step finds. Here each thread appends to its own list, and each chunk records
// where its items lie; the room held is what a whole job found, once per thread.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "world/room.h"
#include "world/workers.h"

namespace cyclone::detail {

template <class T>
class ChunkLists {
public:
    /// Items a chunk appends without a list growing under it: one per item of a chunk,
    /// as a convex pair finds at most one manifold.
    static constexpr std::size_t kRoom = Workers::kChunk;

    /// Empties the lists for a job of `chunks` chunks on `threads` threads. Each list is
    /// given room for the most a job has held so far, so that a steady step allocates
    /// nothing whichever thread takes the most chunks.
    void start(int threads, std::size_t chunks) {
        if (lists_.size() < std::size_t(threads)) lists_.resize(std::size_t(threads));
        for (std::vector<T> &list : lists_) {
            list.clear();
            if (list.capacity() < most_) makeRoom(list, most_);
        }
        spans_.assign(chunks, Span());
    }

    /// The list chunk `chunk`, run on thread `thread`, appends its items to. It has room
    /// for kRoom more items (makeRoom).
    std::vector<T> &open(std::size_t chunk, int thread) {
        std::vector<T> &list = lists_[std::size_t(thread)];
        makeRoom(list, kRoom);
        spans_[chunk] = {thread, list.size(), list.size()};
        return list;
    }

    /// Ends chunk `chunk`'s items (after the appends to the list that open gave).
    void close(std::size_t chunk) {
        Span &span = spans_[chunk];
        span.end = lists_[std::size_t(span.thread)].size();
    }

    /// After the job: counts the items it found (found()), and remembers the most for
    /// start's room.
    void finish() {
        found_ = 0;
        for (const Span &span : spans_) found_ += span.end - span.begin;
        most_ = std::max(most_, found_);
    }

    /// How many items the last finished job found.
    std::size_t found() const { return found_; }

    /// Chunk `chunk`'s items, in the order it appended them.
    struct Items {
        const T *first;
        const T *last;
        const T *begin() const { return first; }
        const T *end() const { return last; }
    };
    Items items(std::size_t chunk) const {
        const Span &span = spans_[chunk];
        const T *data = lists_[std::size_t(span.thread)].data();
        return {data + span.begin, data + span.end};
    }

private:
    struct Span {
        int thread = 0;
        std::size_t begin = 0;
        std::size_t end = 0;
    };
    std::vector<std::vector<T>> lists_;  ///< Per thread.
    std::vector<Span> spans_;            ///< Per chunk of the job.
    std::size_t found_ = 0;              ///< Items the last finished job found.
    std::size_t most_ = 0;               ///< Most items a job has found.
};

}  // namespace cyclone::detail
