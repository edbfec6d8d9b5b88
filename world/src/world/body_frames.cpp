// A body's shape frame, which for a compound is not its centre of mass: the user places a
// compound by the frame its children were given in, while RigidBody moves its centre of
// mass (CollisionShape::frameToCentre is the offset between them).
#include "world/validation.h"
#include "world/world_impl.h"

namespace cyclone {

Vector3 World::framePosition(BodyId id) const {
    const detail::BodyRecord &r = impl_->bodies.record(id, "World::framePosition");
    return r.body.getPosition() - detail::frameToCentre(r.body, *r.shape);
}

Matrix4 World::framePose(BodyId id) const {
    const detail::BodyRecord &r = impl_->bodies.record(id, "World::framePose");
    Matrix4 pose = r.body.getTransform();
    pose.translation() -= detail::frameToCentre(r.body, *r.shape);
    return pose;
}

Vector3 World::localCentreOfMass(BodyId id) const {
    return impl_->bodies.record(id, "World::localCentreOfMass").shape->frameToCentre();
}

void World::setFramePosition(BodyId id, const Vector3 &position) {
    static const char *function = "World::setFramePosition";
    const detail::BodyRecord &r = impl_->bodies.record(id, function);
    detail::requirePlace(function, "position", position);
    const Vector3 centre = position + detail::frameToCentre(r.body, *r.shape);
    if (!centre.allFinite() || centre.cwiseAbs().maxCoeff() > detail::kMaxCoordinate)
        detail::refuse(function, "position", "puts the centre of mass beyond 1e12 m, got " + detail::show(position));
    setPosition(id, centre);
}

}  // namespace cyclone
