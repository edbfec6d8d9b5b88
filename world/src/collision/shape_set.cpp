#include "collision/shape_set.h"

#include <cstring>
#include <iterator>
#include <utility>

namespace cyclone::detail {

namespace {

/// A piece of a description: bytes that two equal descriptions hold alike.
struct Span {
    const void *data;
    std::size_t size;
};

template <class T>
Span spanOf(const T &value) {
    return {&value, sizeof value};
}

template <class T>
Span spanOf(const std::vector<T> &values) {
    return {values.data(), values.size() * sizeof(T)};
}

// Every field of `s` and of its children. A list's span is as long as the list, so two
// lists of spans are equal span by span, sizes and bytes, only when the descriptions are.
// The fields are plain values (no padding inside Eigen's vectors and quaternions).
void appendSpans(const Shape &s, std::vector<Span> &out) {
    const Span fields[] = {spanOf(s.type),    {s.halfExtents.data(), sizeof(real) * 3},
                           spanOf(s.radius),  spanOf(s.length),
                           spanOf(s.vertices), spanOf(s.triangles),
                           spanOf(s.sides),   {s.normal.data(), sizeof(real) * 3},
                           spanOf(s.offset),  spanOf(s.rows),
                           spanOf(s.columns), spanOf(s.spacing),
                           spanOf(s.heights)};
    out.insert(out.end(), std::begin(fields), std::end(fields));
    for (const CompoundChild &child : s.children) {
        out.push_back({child.position.data(), sizeof(real) * 3});
        out.push_back({child.orientation.coeffs().data(), sizeof(real) * 4});
        appendSpans(child.shape, out);
    }
}

std::vector<Span> spansOf(const Shape &s) {
    std::vector<Span> spans;
    appendSpans(s, spans);
    return spans;
}

bool sameBits(const std::vector<Span> &a, const std::vector<Span> &b) {
    if (a.size() != b.size()) return false;
    for (std::size_t k = 0; k < a.size(); ++k)
        if (a[k].size != b[k].size || (a[k].size > 0 && std::memcmp(a[k].data, b[k].data, a[k].size) != 0)) return false;
    return true;
}

// FNV-1a over the spans' sizes and bytes.
std::uint64_t hashOf(const std::vector<Span> &spans) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    const auto feed = [&h](const void *data, std::size_t size) {
        const auto *bytes = static_cast<const unsigned char *>(data);
        for (std::size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 0x100000001b3ull;
    };
    for (const Span &span : spans) {
        feed(&span.size, sizeof span.size);
        feed(span.data, span.size);
    }
    return h;
}

}  // namespace

std::optional<std::uint32_t> ShapeSet::find(const Shape &description) const {
    const std::vector<Span> spans = spansOf(description);
    const auto [first, last] = places_.equal_range(hashOf(spans));
    for (auto it = first; it != last; ++it)
        if (sameBits(spans, spansOf(shapes_[it->second]->shape()))) return it->second;
    return std::nullopt;
}

std::uint32_t ShapeSet::add(std::shared_ptr<const CollisionShape> shape) {
    const auto place = static_cast<std::uint32_t>(shapes_.size());
    places_.emplace(hashOf(spansOf(shape->shape())), place);
    shapes_.push_back(std::move(shape));
    return place;
}

}  // namespace cyclone::detail
