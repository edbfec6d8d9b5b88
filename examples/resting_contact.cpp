// Resting contact: one body of each shape at rest on a plane and on a static box, and a
// box on a 30 degree incline that holds with friction 0.7 and slides with 0.3.
#include <cmath>
#include <cstdio>

#include "cyclone/world.h"

using namespace cyclone;

namespace {

const double kPi = 3.14159265358979323846;

// Rotates local z (the axis of capsules and cylinders) onto world y, or onto world x.
Quaternion zToY() { return Quaternion(Eigen::AngleAxis<real>(-kPi / 2, Vector3::UnitX())); }

std::vector<std::pair<const char *, BodySettings>> shapes() {
    std::vector<std::pair<const char *, BodySettings>> out;
    BodySettings s;
    s.shape = Shape::box(Vector3(0.3, 0.2, 0.4));
    out.push_back({"box", s});
    s.shape = Shape::sphere(0.3);
    out.push_back({"sphere", s});
    s.shape = Shape::capsule(0.2, 0.6);  // lying on its side
    out.push_back({"capsule (side)", s});
    s.shape = Shape::cylinder(0.3, 0.5);
    s.orientation = zToY();  // standing on a cap
    out.push_back({"cylinder (cap)", s});
    s.orientation = Quaternion::Identity();
    s.shape = Shape::convex({{-0.3, -0.2, -0.3}, {0.3, -0.2, -0.3}, {0.3, -0.2, 0.3}, {-0.3, -0.2, 0.3},
                             {0, 0.3, 0}, {0.2, 0.1, 0.1}});
    out.push_back({"convex", s});
    return out;
}

// Lowest point of a shape below its origin, for placing it resting on a surface.
double lowest(const BodySettings &s) {
    switch (s.shape.type) {
        case ShapeType::Box: return s.shape.halfExtents.y();
        case ShapeType::Sphere:
        case ShapeType::Capsule: return s.shape.radius;
        case ShapeType::Cylinder: return s.shape.length / 2;
        default: return 0.2;
    }
}

void restOn(bool onBox) {
    WorldSettings ws;
    ws.sleep = false;
    World world(ws);
    BodySettings support;
    support.motion = Motion::Static;
    if (onBox) {
        support.shape = Shape::box(Vector3(6, 0.5, 2));
        support.position = Vector3(0, -0.5, 0);
    } else {
        support.shape = Shape::plane(Vector3::UnitY(), 0);
    }
    world.addBody(support);
    std::vector<std::pair<const char *, BodyId>> ids;
    double x = -4;
    for (auto [name, s] : shapes()) {
        s.position = Vector3(x, lowest(s), 0);
        ids.push_back({name, world.addBody(s)});
        x += 2;
    }
    std::vector<Vector3> start;
    for (auto &[name, id] : ids) start.push_back(world.body(id).getPosition());
    double deepest = 0;
    for (int i = 0; i < 300; ++i) {
        world.step(1.0 / 60.0);
        deepest = std::max(deepest, double(world.stats().maxPenetration));
    }
    std::printf("on a %s (5 s, sleep off), deepest contact %.4f m:\n", onBox ? "static box" : "plane", deepest);
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const RigidBody &b = world.body(ids[i].second);
        std::printf("  %-16s moved %.5f m, speed %.5f m/s\n", ids[i].first, (b.getPosition() - start[i]).norm(),
                    b.getVelocity().norm());
    }
}

void incline(double friction) {
    const double theta = 30 * kPi / 180;
    World world;
    BodySettings ramp;
    ramp.motion = Motion::Static;
    ramp.shape = Shape::box(Vector3(10, 0.25, 2));
    ramp.orientation = Quaternion(Eigen::AngleAxis<real>(theta, Vector3::UnitZ()));
    ramp.material.friction = friction;
    world.addBody(ramp);
    const Vector3 up = ramp.orientation * Vector3::UnitY();
    const Vector3 downhill = ramp.orientation * -Vector3::UnitX();
    BodySettings box;
    box.shape = Shape::box(Vector3(0.25, 0.25, 0.25));
    box.orientation = ramp.orientation;
    box.position = up * 0.5;
    box.material.friction = friction;
    const BodyId id = world.addBody(box);
    for (int i = 0; i < 30; ++i) world.step(1.0 / 60.0);  // settle into contact
    const double s0 = world.body(id).getPosition().dot(downhill);
    const double v0 = world.body(id).getVelocity().dot(downhill);
    const double t = 1.0;
    for (int i = 0; i < 60; ++i) world.step(1.0 / 60.0);
    const double s1 = world.body(id).getPosition().dot(downhill);
    // s1 - s0 = v0 t + a t^2 / 2
    const double measured = 2 * (s1 - s0 - v0 * t) / (t * t);
    const double expected = std::max(0.0, 9.81 * (std::sin(theta) - friction * std::cos(theta)));
    std::printf("incline 30 deg, friction %.1f: acceleration %.3f m/s^2 (Coulomb: %.3f), slid %.4f m in 1 s\n",
                friction, measured, expected, s1 - s0);
}

}  // namespace

int main() {
    restOn(false);
    restOn(true);
    incline(0.7);
    incline(0.3);
    return 0;
}
