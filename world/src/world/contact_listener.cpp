// World::setContactListener: the user's side of the pre-solve stage (contacts/pre_solve.h).
#include "world/world_impl.h"

namespace cyclone {

void World::setContactListener(ContactListener *listener) { impl_->preSolve.listener = listener; }

ContactListener *World::contactListener() const { return impl_->preSolve.listener; }

}  // namespace cyclone
