// The bytes of a saved World state: a header (a tag, the format's version, the payload's
// length and checksum), then the payload, written and read field by field through one
// call, io(archive, field), so that each struct's fields are listed once for both
// directions (snapshot/world_state_io.cpp).
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>
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
    std::size_t size() const { return out_.size(); }
    void bytes(const void *data, std::size_t size) {
        const std::size_t at = out_.size();
        out_.resize(at + size);
        if (size > 0) std::memcpy(out_.data() + at, data, size);
    }
    void byte(std::uint8_t b) { out_.push_back(b); }
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
    std::uint8_t byte() {
        if (at_ == end_) throw UnreadableState{"it is cut short"};
        return *at_++;
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

/// An unsigned number seven bits a byte, low bits first, the high bit set on every byte
/// but the last: numbers below 128 take one byte (indices, counts, step differences).
template <class Archive, class T>
void packed(Archive &archive, T &value) {
    static_assert(std::is_unsigned_v<T>, "packed numbers are unsigned");
    if constexpr (Archive::kReading) {
        std::uint64_t v = 0;
        for (int shift = 0;; shift += 7) {
            if (shift >= 64) throw UnreadableState{"a packed number is too long"};
            const std::uint8_t b = archive.byte();
            v |= std::uint64_t(b & 0x7F) << shift;
            if (!(b & 0x80)) break;
        }
        if (v > std::numeric_limits<T>::max()) throw UnreadableState{"a packed number is out of range"};
        value = static_cast<T>(v);
    } else {
        std::uint64_t v = value;
        for (; v >= 0x80; v >>= 7) archive.byte(static_cast<std::uint8_t>(v | 0x80));
        archive.byte(static_cast<std::uint8_t>(v));
    }
}

/// A list of unsigned numbers, packed.
template <class Archive, class T>
void packed(Archive &archive, std::vector<T> &items) {
    const std::size_t n = archive.count(items.size());
    if constexpr (Archive::kReading) items.resize(n);
    for (T &item : items) packed(archive, item);
}

/// A step number packed as how many steps before `now` it was (0: `now`; any number,
/// "never" included, reads back: the difference wraps around).
template <class Archive>
void packedStep(Archive &archive, std::uint64_t &step, std::uint64_t now) {
    std::uint64_t before = now - step;
    packed(archive, before);
    if constexpr (Archive::kReading) step = now - before;
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
