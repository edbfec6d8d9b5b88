// The scenes in a cyclone::World: the scene description is already in the World's terms.
#include <vector>

#include "cyclone/world/world.h"
#include "engine.h"

namespace cyclone::bench {
namespace {

class CycloneEngine final : public Engine {
public:
    explicit CycloneEngine(const Scene &scene) : world_(scene.world) {
        ids_.reserve(scene.bodies.size());
        for (const BodySettings &settings : scene.bodies) ids_.push_back(world_.addBody(settings));
    }

    void step(real dt) override { world_.step(dt); }
    Vector3 position(int index) const override {
        return world_.body(ids_[static_cast<std::size_t>(index)]).getPosition();
    }
    real deepestPenetration() const override { return world_.stats().maxPenetration; }
    int contacts() const override { return world_.stats().contacts; }

private:
    World world_;
    std::vector<BodyId> ids_;
};

}  // namespace

std::unique_ptr<Engine> makeCycloneEngine(const Scene &scene) { return std::make_unique<CycloneEngine>(scene); }

}  // namespace cyclone::bench
