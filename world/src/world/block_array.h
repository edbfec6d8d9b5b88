// An array that grows a block at a time and never moves what it holds: for large
// elements that are kept from step to step (the solver's manifolds, 2.3 KB each). A
// std::vector that outgrows its room copies everything into a buffer twice as large,
// and holds both while it copies: three times the elements' bytes at that moment, and
// twice them for good. Here growing adds blocks, and the room past the size is less
// than one block.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <iterator>
#include <memory>
#include <vector>

namespace cyclone::detail {

/// Elements by index, in blocks of kBlock; blocks are kept when the size falls, so that
/// a size reached once costs no allocation again.
template <class T, std::size_t kBlock = 64>
class BlockArray {
public:
    BlockArray() = default;
    BlockArray(std::initializer_list<T> elements) {
        for (const T &e : elements) push_back(e);
    }
    BlockArray(const BlockArray &other) { *this = other; }
    BlockArray(BlockArray &&) noexcept = default;
    BlockArray &operator=(const BlockArray &other) {
        if (this == &other) return *this;
        resize(other.size_);
        for (std::size_t i = 0; i < size_; ++i) (*this)[i] = other[i];
        return *this;
    }
    BlockArray &operator=(BlockArray &&) noexcept = default;

    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }

    T &operator[](std::size_t i) { return blocks_[i / kBlock][i % kBlock]; }
    const T &operator[](std::size_t i) const { return blocks_[i / kBlock][i % kBlock]; }

    /// As std::vector::resize: elements past the old size are value-initialised (T{}),
    /// those below keep what they hold.
    void resize(std::size_t n) {
        while (blocks_.size() * kBlock < n) blocks_.push_back(std::make_unique<T[]>(kBlock));
        for (std::size_t i = size_; i < n; ++i) (*this)[i] = T{};
        size_ = n;
    }
    /// Size n, every element `value`.
    void assign(std::size_t n, const T &value) {
        resize(n);
        for (std::size_t i = 0; i < n; ++i) (*this)[i] = value;
    }
    void push_back(const T &element) {
        resize(size_ + 1);
        (*this)[size_ - 1] = element;
    }
    /// Size 0; the blocks are kept.
    void clear() { size_ = 0; }

    template <class Array, class Element>
    class Iterator {
    public:
        using iterator_category = std::forward_iterator_tag;
        using value_type = T;
        using difference_type = std::ptrdiff_t;
        using pointer = Element *;
        using reference = Element &;

        Iterator(Array *array, std::size_t i) : array_(array), i_(i) {}
        Element &operator*() const { return (*array_)[i_]; }
        Element *operator->() const { return &(*array_)[i_]; }
        Iterator &operator++() {
            ++i_;
            return *this;
        }
        bool operator==(const Iterator &other) const { return i_ == other.i_; }
        bool operator!=(const Iterator &other) const { return i_ != other.i_; }

    private:
        Array *array_;
        std::size_t i_;
    };

    Iterator<BlockArray, T> begin() { return {this, 0}; }
    Iterator<BlockArray, T> end() { return {this, size_}; }
    Iterator<const BlockArray, const T> begin() const { return {this, 0}; }
    Iterator<const BlockArray, const T> end() const { return {this, size_}; }

private:
    std::vector<std::unique_ptr<T[]>> blocks_;
    std::size_t size_ = 0;
};

}  // namespace cyclone::detail
