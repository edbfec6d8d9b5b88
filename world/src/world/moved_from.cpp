// What a call on a moved-from World does: throw, naming the misuse; and the count of
// calls that may change the World, which read-only callbacks are checked against.
#include "world/validation.h"
#include "world/world_impl.h"

namespace cyclone {

World::State::State() = default;
World::State::~State() = default;
World::State::State(State &&) noexcept = default;
World::State &World::State::operator=(State &&) noexcept = default;

World::State &World::State::operator=(std::unique_ptr<Impl> impl) {
    impl_ = std::move(impl);
    return *this;
}

World::Impl *World::State::changing() {
    Impl *impl = get();
    ++impl->changingCalls;
    return impl;
}

void World::State::throwMovedFrom() {
    detail::refuse("World", "this", "is a moved-from World: it may only be destroyed or assigned to");
}

}  // namespace cyclone
