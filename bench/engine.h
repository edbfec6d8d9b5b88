// What the harness needs from a physics engine: build a scene, step it, and report the
// tracked body's position, the deepest penetration and the contact count of the last step.
#pragma once

#include <memory>
#include <string>

#include "scenes.h"

namespace cyclone::bench {

class Engine {
public:
    virtual ~Engine() = default;
    /// Advances the scene by one step of `dt` seconds.
    virtual void step(real dt) = 0;
    /// World-space position of body `index` of the scene (index into Scene::bodies), m.
    virtual Vector3 position(int index) const = 0;
    /// Deepest penetration among the contacts of the last step, m, >= 0.
    virtual real deepestPenetration() const = 0;
    /// Contact points of the last step.
    virtual int contacts() const = 0;
};

/// The scene in a cyclone::World.
std::unique_ptr<Engine> makeCycloneEngine(const Scene &scene);

#ifdef CYCLONE_BENCH_HAVE_BULLET
/// The scene in a Bullet btDiscreteDynamicsWorld (see bullet_engine.cpp for the settings).
std::unique_ptr<Engine> makeBulletEngine(const Scene &scene);
/// Bullet's version, precision and the solver settings used, as Markdown list items.
std::string bulletSettingsNote();
#endif

}  // namespace cyclone::bench
