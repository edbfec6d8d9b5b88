// Scene descriptions. Every random choice comes from a fixed-seed generator of our own,
// so that each engine, run and machine sees exactly the same bodies.
#include "scenes.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "cyclone/world.h"

namespace cyclone::bench {
namespace {

constexpr real kPi = 3.14159265358979323846;

// splitmix64: tiny, and its output does not depend on the standard library, unlike
// std::uniform_real_distribution.
class Random {
public:
    explicit Random(std::uint64_t seed) : state_(seed) {}
    real uniform() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        z ^= z >> 31;
        return static_cast<real>(z >> 11) * 0x1.0p-53;
    }
    real uniform(real low, real high) { return low + (high - low) * uniform(); }
    // Uniformly distributed rotation (Shoemake's subgroup algorithm).
    Quaternion orientation() {
        const real u1 = uniform(), u2 = uniform(), u3 = uniform();
        const real a = std::sqrt(1 - u1), b = std::sqrt(u1);
        return Quaternion(b * std::cos(2 * kPi * u3), a * std::sin(2 * kPi * u2), a * std::cos(2 * kPi * u2),
                          b * std::sin(2 * kPi * u3));
    }

private:
    std::uint64_t state_;
};

WorldSettings worldSettings(bool sleep) {
    WorldSettings settings;
    settings.substeps = 1;
    settings.velocityIterations = kVelocityPassesPerFrame;
    settings.sleep = sleep;
    return settings;
}

BodySettings staticBody(std::string name, Shape shape, const Vector3 &position) {
    BodySettings b;
    b.name = std::move(name);
    b.shape = std::move(shape);
    b.motion = Motion::Static;
    b.position = position;
    return b;
}

BodySettings ground() { return staticBody("ground", Shape::plane(Vector3::UnitY(), 0), Vector3::Zero()); }

BodySettings dynamicBody(std::string name, Shape shape, const Vector3 &position) {
    BodySettings b;
    b.name = std::move(name);
    b.shape = std::move(shape);
    b.mass = 1;
    b.position = position;
    return b;
}

// A rock: an icosahedron of radius about `radius` whose vertices are pushed in or out
// at random, then shifted so that their mean is the origin.
std::vector<Vector3> rockPoints(Random &random, real radius) {
    const real phi = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vector3> points;
    for (real s1 : {-1.0, 1.0}) {
        for (real s2 : {-1.0, 1.0}) {
            points.emplace_back(0, s1, s2 * phi);
            points.emplace_back(s1, s2 * phi, 0);
            points.emplace_back(s2 * phi, 0, s1);
        }
    }
    Vector3 mean = Vector3::Zero();
    for (Vector3 &p : points) {
        p = p.normalized() * radius * random.uniform(0.8, 1.2);
        mean += p;
    }
    mean /= static_cast<real>(points.size());
    for (Vector3 &p : points) p -= mean;
    return points;
}

// Unit boxes in a pyramid of `base` boxes at the bottom, 1.05 m apart horizontally and
// touching vertically, on the ground plane; the last body is the top box.
Scene pyramid(int base) {
    Scene scene;
    scene.name = "pyramid" + std::to_string(base);
    scene.description = "box pyramid of base " + std::to_string(base) + " (" + std::to_string(base * (base + 1) / 2) +
                        " unit boxes, 1.05 m apart, touching vertically) on a ground plane, sleep off";
    scene.world = worldSettings(false);
    scene.bodies.push_back(ground());
    for (int layer = 0; layer < base; ++layer) {
        const int count = base - layer;
        for (int i = 0; i < count; ++i) {
            const real x = (i - (count - 1) / 2.0) * 1.05;
            const real y = 0.5 + layer;
            scene.bodies.push_back(dynamicBody("box" + std::to_string(layer) + "_" + std::to_string(i),
                                               Shape::box(Vector3(0.5, 0.5, 0.5)), Vector3(x, y, 0)));
        }
    }
    scene.tracked = static_cast<int>(scene.bodies.size()) - 1;
    return scene;
}

// columns x rows x layers bodies, one in five of each kind, dropped from a grid 0.95 m
// apart with random orientations (none overlapping another) into a walled box of
// columns x rows metres with 6 m walls (mixed1000: 10 x 10 x 10 into 10 m x 10 m;
// mixed5000: 25 x 20 x 10 into 25 m x 20 m, the same pile per square metre).
Scene mixed(std::uint64_t seed, int columns, int rows, int layers) {
    Scene scene;
    const int count = columns * rows * layers;
    scene.name = "mixed" + std::to_string(count);
    scene.world = worldSettings(true);
    scene.description = std::to_string(count) +
                        " boxes, spheres, capsules, cylinders and convex hulls (1 kg, 0.5-0.8 m across) falling into a " +
                        std::to_string(columns) + " m x " + std::to_string(rows) + " m walled box, sleep on";
    scene.bodies.push_back(ground());
    const real innerX = columns / 2.0, innerZ = rows / 2.0, thickness = 0.25, height = 3;
    scene.bodies.push_back(staticBody("wall_x-", Shape::box(Vector3(thickness, height, innerZ + 2 * thickness)),
                                      Vector3(-innerX - thickness, height, 0)));
    scene.bodies.push_back(staticBody("wall_x+", Shape::box(Vector3(thickness, height, innerZ + 2 * thickness)),
                                      Vector3(innerX + thickness, height, 0)));
    scene.bodies.push_back(staticBody("wall_z-", Shape::box(Vector3(innerX, height, thickness)),
                                      Vector3(0, height, -innerZ - thickness)));
    scene.bodies.push_back(staticBody("wall_z+", Shape::box(Vector3(innerX, height, thickness)),
                                      Vector3(0, height, innerZ + thickness)));

    Random random(0x5EEDC1C10E5ull ^ seed);
    std::vector<std::vector<Vector3>> rocks;
    for (int i = 0; i < 5; ++i) rocks.push_back(rockPoints(random, 0.3));
    // The bodies placed so far, to test each new one against: two long shapes turned
    // towards each other across the 0.95 m grid may overlap. Such a body takes another
    // orientation, from a stream of its own, so that the others stay as they were.
    World placed;
    std::vector<BodyId> hits;
    int index = 0;
    for (int layer = 0; layer < layers; ++layer) {
        for (int row = 0; row < rows; ++row) {
            for (int column = 0; column < columns; ++column, ++index) {
                Shape shape;
                switch (index % 5) {
                case 0:
                    shape = Shape::box(Vector3(random.uniform(0.2, 0.35), random.uniform(0.2, 0.35),
                                             random.uniform(0.2, 0.35)));
                    break;
                case 1: shape = Shape::sphere(random.uniform(0.25, 0.35)); break;
                case 2: shape = Shape::capsule(0.2, random.uniform(0.3, 0.4)); break;
                case 3: shape = Shape::cylinder(random.uniform(0.25, 0.3), random.uniform(0.4, 0.6)); break;
                default: shape = Shape::convex(rocks[static_cast<std::size_t>(index / 5 % 5)]); break;
                }
                const Vector3 position((column - (columns - 1) / 2.0) * 0.95, 1 + layer,
                                       (row - (rows - 1) / 2.0) * 0.95);
                BodySettings body = dynamicBody("body" + std::to_string(index), std::move(shape), position);
                body.orientation = random.orientation();
                Random again(0xA9A1Bull ^ (seed << 16) ^ static_cast<std::uint64_t>(index));
                while (placed.overlap(body.shape, body.position, body.orientation, hits) > 0)
                    body.orientation = again.orientation();
                placed.addBody(body);
                scene.bodies.push_back(std::move(body));
            }
        }
    }
    return scene;
}

// The bouncing sphere of the sleeping scene: dropped from 5 m with restitution 0.9
// (the ground has 0; a pair bounces with the larger of its two), never allowed to sleep.
BodySettings bouncingSphere() {
    BodySettings sphere = dynamicBody("sphere", Shape::sphere(0.5), Vector3(-30, 5, 0));
    sphere.material.restitution = 0.9;
    sphere.canSleep = false;
    return sphere;
}

// 100 stacks of 10 unit boxes, 2 m apart, asleep from the start, plus the bouncing
// sphere 20 m away from the nearest stack.
Scene sleeping() {
    Scene scene;
    scene.name = "sleeping1000";
    scene.world = worldSettings(true);
    scene.description =
        "1000 unit boxes in 100 stacks of 10, asleep from the start, plus one bouncing sphere 20 m away, sleep on";
    scene.bodies.push_back(ground());
    for (int row = 0; row < 10; ++row) {
        for (int column = 0; column < 10; ++column) {
            for (int level = 0; level < 10; ++level) {
                BodySettings box = dynamicBody(
                    "box" + std::to_string(row) + "_" + std::to_string(column) + "_" + std::to_string(level),
                    Shape::box(Vector3(0.5, 0.5, 0.5)), Vector3((column - 4.5) * 2, 0.5 + level, (row - 4.5) * 2));
                box.awake = false;
                scene.bodies.push_back(std::move(box));
            }
        }
    }
    scene.tracked = 10;  // the top box of the first stack
    scene.bodies.push_back(bouncingSphere());
    return scene;
}

// The awake body of "sleeping1000" alone: the reference cost that the sleeping boxes
// should hardly add to.
Scene sphereAlone() {
    Scene scene;
    scene.name = "sphere_alone";
    scene.world = worldSettings(true);
    scene.description = "the bouncing sphere of sleeping1000 alone on the ground plane (reference cost), sleep on";
    scene.bodies.push_back(ground());
    scene.bodies.push_back(bouncingSphere());
    return scene;
}

}  // namespace

std::vector<std::string> sceneNames() {
    return {"pyramid10",  "pyramid20",  "pyramid40", "pyramid60", "pyramid100",   "pyramid150",
            "pyramid200", "mixed1000", "mixed5000", "sleeping1000", "sphere_alone"};
}

Scene makeScene(const std::string &name, std::uint64_t seed) {
    if (name == "pyramid10") return pyramid(10);
    if (name == "pyramid20") return pyramid(20);
    if (name == "pyramid40") return pyramid(40);
    if (name == "pyramid60") return pyramid(60);
    if (name == "pyramid100") return pyramid(100);
    if (name == "pyramid150") return pyramid(150);
    if (name == "pyramid200") return pyramid(200);
    if (name == "mixed1000") return mixed(seed, 10, 10, 10);
    if (name == "mixed5000") return mixed(seed, 25, 20, 10);
    if (name == "sleeping1000") return sleeping();
    if (name == "sphere_alone") return sphereAlone();
    throw std::invalid_argument("makeScene: name \"" + name + "\" is not a scene (see --list)");
}

void useWorldDefaults(WorldSettings &settings) {
    const WorldSettings defaults;
    settings.substeps = defaults.substeps;
    settings.velocityIterations = defaults.velocityIterations;
    settings.positionIterations = defaults.positionIterations;
}

void splitSubsteps(Scene &scene, int substeps) {
    const int passes = scene.world.substeps * scene.world.velocityIterations;
    if (substeps < 1 || passes % substeps != 0) {
        throw std::invalid_argument("splitSubsteps: substeps must divide the " + std::to_string(passes) +
                                    " velocity passes per frame, got " + std::to_string(substeps));
    }
    scene.world.substeps = substeps;
    scene.world.velocityIterations = passes / substeps;
}

std::vector<std::string> splitSceneList(const std::string &list) {
    std::vector<std::string> names;
    std::stringstream stream(list);
    std::string name;
    while (std::getline(stream, name, ','))
        if (!name.empty()) names.push_back(name);
    return names;
}

bool readSceneOption(const std::string &option, const std::string &value, std::vector<std::string> &scenes,
                     int &steps, int &threads) {
    if (option == "--scene") {
        for (const std::string &name : splitSceneList(value)) scenes.push_back(name);
    } else if (option == "--steps") {
        steps = std::atoi(value.c_str());
    } else if (option == "--threads") {
        threads = std::atoi(value.c_str());
    } else {
        return false;
    }
    return true;
}

}  // namespace cyclone::bench
