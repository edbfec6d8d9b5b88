// A small mixed pile for the narrowphase's tests: boxes, spheres, capsules, cylinders and
// convex hulls dropped into a walled box, so that every kind of shape pair goes through
// the narrowphase (FCL and libccd for the curved shapes and hulls).
#pragma once

#include <vector>

#include "cyclone/world.h"

namespace cyclone::test {

/// An irregular hull about 0.6 m across (ten points, none inside the others' hull).
inline Shape pileRock() {
    return Shape::convex({Vector3(0.3, 0, 0), Vector3(-0.28, 0.05, 0.02), Vector3(0, 0.27, 0.03),
                          Vector3(0.02, -0.3, -0.01), Vector3(0.01, 0.02, 0.29), Vector3(-0.03, 0, -0.31),
                          Vector3(0.18, 0.18, 0.16), Vector3(-0.17, -0.17, 0.17), Vector3(0.17, -0.18, -0.16),
                          Vector3(-0.18, 0.17, -0.17)});
}

/// columns x columns x layers bodies, the five kinds in turn, dropped from a grid 0.95 m
/// apart, each tilted differently, into a walled columns m x columns m box on a ground
/// plane. Returns the dynamic bodies' ids in the order added.
inline std::vector<BodyId> addMixedPile(World &world, int columns, int layers) {
    BodySettings ground;
    ground.motion = Motion::Static;
    ground.shape = Shape::plane(Vector3::UnitY(), 0);
    world.addBody(ground);
    const real inner = columns / 2.0;
    for (int side = 0; side < 4; ++side) {
        BodySettings wall;
        wall.motion = Motion::Static;
        const bool alongX = side < 2;
        const real sign = side % 2 == 0 ? -1 : 1;
        wall.shape = Shape::box(alongX ? Vector3(0.25, 2, inner + 0.5) : Vector3(inner, 2, 0.25));
        wall.position = alongX ? Vector3(sign * (inner + 0.25), 2, 0) : Vector3(0, 2, sign * (inner + 0.25));
        world.addBody(wall);
    }
    std::vector<BodyId> ids;
    int index = 0;
    for (int layer = 0; layer < layers; ++layer) {
        for (int row = 0; row < columns; ++row) {
            for (int column = 0; column < columns; ++column, ++index) {
                BodySettings body;
                switch (index % 5) {
                    case 0: body.shape = Shape::box(Vector3(0.3, 0.25, 0.2)); break;
                    case 1: body.shape = Shape::sphere(0.3); break;
                    case 2: body.shape = Shape::capsule(0.2, 0.35); break;
                    case 3: body.shape = Shape::cylinder(0.28, 0.5); break;
                    default: body.shape = pileRock(); break;
                }
                body.position = Vector3((column - (columns - 1) / 2.0) * 0.95, 0.6 + layer,
                                        (row - (columns - 1) / 2.0) * 0.95);
                body.orientation = Quaternion(1, 0.3 * (index % 7) - 0.9, 0.2 * (index % 3), 0.1 * (index % 5)).normalized();
                ids.push_back(world.addBody(body));
            }
        }
    }
    return ids;
}

}  // namespace cyclone::test
