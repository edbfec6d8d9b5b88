// The shapes a World's bodies were added with, each compiled once: bodies whose
// descriptions are equal bit for bit share one compiled shape (its FCL geometry, hull
// faces and edges), as a pile of a few kinds of rock shares five hulls, not two hundred.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "collision/collision_shape.h"

namespace cyclone::detail {

class ShapeSet {
public:
    /// The place of the shape compiled from a description equal to `description` bit for
    /// bit (every field, used by its type or not), if there is one.
    std::optional<std::uint32_t> find(const Shape &description) const;
    /// Appends `shape` (compiled from a description find() does not know); returns its place.
    std::uint32_t add(std::shared_ptr<const CollisionShape> shape);
    const std::shared_ptr<const CollisionShape> &operator[](std::uint32_t place) const { return shapes_[place]; }
    /// Every shape, in the order added: a saved state names its bodies' shapes by place.
    const std::vector<std::shared_ptr<const CollisionShape>> &all() const { return shapes_; }
    std::size_t size() const { return shapes_.size(); }

private:
    std::vector<std::shared_ptr<const CollisionShape>> shapes_;
    /// Places by a hash of their descriptions' bits.
    std::unordered_multimap<std::uint64_t, std::uint32_t> places_;
};

}  // namespace cyclone::detail
