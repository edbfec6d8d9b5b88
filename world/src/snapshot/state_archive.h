// The bytes of a saved World state: a header (a tag, the format's version, the payload's
// length and checksum), then the payload, written and read field by field through one
// call, io(archive, field), so that each struct's fields are listed once for both
// directions (snapshot/world_state_io.cpp).
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace cyclone::detail {

/// Why a state cannot be read (its checksum fails, or it is cut short): the World refuses
/// it with this text.
struct UnreadableState {
    std::string problem;
};

/// Appends fields to a byte vector.
class StateWriter {
public:
    static constexpr bool kReading = false;
    explicit StateWriter(std::vector<std::uint8_t> &out) : out_(out) {}
    void bytes(const void *data, std::size_t size) {
        const auto *b = static_cast<const std::uint8_t *>(data);
        out_.insert(out_.end(), b, b + size);
    }
    /// Writes a count and returns it (the item size matters only when reading).
    std::size_t count(std::size_t n, std::size_t = 1) {
        const auto value = static_cast<std::uint32_t>(n);
        bytes(&value, sizeof value);
        return n;
    }

private:
    std::vector<std::uint8_t> &out_;
};

/// Reads fields back from bytes, refusing (UnreadableState) to read past their end.
class StateReader {
public:
    static constexpr bool kReading = true;
    StateReader(const std::uint8_t *data, std::size_t size) : at_(data), end_(data + size) {}
    void bytes(void *data, std::size_t size) {
        if (size > static_cast<std::size_t>(end_ - at_)) throw UnreadableState{"it is cut short"};
        if (size > 0) std::memcpy(data, at_, size);
        at_ += size;
    }
    /// Reads a count of items at least `itemSize` bytes each, refused when the bytes left
    /// cannot hold them (so that a damaged count allocates nothing).
    std::size_t count(std::size_t, std::size_t itemSize = 1) {
        std::uint32_t value = 0;
        bytes(&value, sizeof value);
        if (itemSize > 0 && value > static_cast<std::size_t>(end_ - at_) / itemSize)
            throw UnreadableState{"a count exceeds its bytes"};
        return value;
    }
    bool done() const { return at_ == end_; }

private:
    const std::uint8_t *at_;
    const std::uint8_t *end_;
};

/// Whether a value is copied as its bytes: numbers, enums, Eigen's fixed-size matrices and
/// the structs made of them, which own nothing (unlike a vector or a string, whose
/// destructors are not trivial). A struct holding a pointer has its own io().
template <class T>
inline constexpr bool kCopiedAsBytes = std::is_trivially_destructible_v<T> && !std::is_pointer_v<T>;

/// A value copied as its bytes.
template <class Archive, class T>
std::enable_if_t<kCopiedAsBytes<T>> io(Archive &archive, T &value) {
    archive.bytes(&value, sizeof value);
}

template <class Archive>
void io(Archive &archive, std::string &text) {
    const std::size_t n = archive.count(text.size());
    if constexpr (Archive::kReading) text.resize(n);
    archive.bytes(text.data(), n);
}

template <class Archive, class T>
void io(Archive &archive, std::vector<T> &items) {
    std::size_t n;
    if constexpr (Archive::kReading) {
        n = archive.count(0, kCopiedAsBytes<T> ? sizeof(T) : 1);
        items.resize(n);
    } else {
        n = archive.count(items.size());
    }
    if constexpr (kCopiedAsBytes<T>) {
        archive.bytes(items.data(), n * sizeof(T));
    } else {
        for (T &item : items) io(archive, item);
    }
}

/// Several fields in a row: io(archive, a, b, c).
template <class Archive, class T, class U, class... More>
void io(Archive &archive, T &first, U &second, More &...more) {
    io(archive, first);
    io(archive, second, more...);
}

/// A 64-bit checksum of `size` bytes (eight at a time, then the rest), for telling a
/// damaged state from a sound one.
inline std::uint64_t stateChecksum(const std::uint8_t *data, std::size_t size) {
    std::uint64_t h = 0x9E3779B97F4A7C15ull ^ size;
    std::size_t k = 0;
    for (; k + 8 <= size; k += 8) {
        std::uint64_t word;
        std::memcpy(&word, data + k, 8);
        h = (h ^ word) * 0xFF51AFD7ED558CCDull;
        h ^= h >> 29;
    }
    for (; k < size; ++k) h = (h ^ data[k]) * 0x100000001B3ull;
    return h ^ (h >> 32);
}

}  // namespace cyclone::detail
