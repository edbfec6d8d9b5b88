#include "world_view.h"

#include <cmath>

namespace cyclone::viewer {

namespace {

void pushLine(std::vector<LineVertex> &out, const Eigen::Vector3f &from, const Eigen::Vector3f &to, const Rgb &c) {
    out.push_back({{from.x(), from.y(), from.z()}, {c.r, c.g, c.b}});
    out.push_back({{to.x(), to.y(), to.z()}, {c.r, c.g, c.b}});
}

// The World's debug drawing, collected as line vertices.
class LineCollector : public DebugDraw {
public:
    explicit LineCollector(std::vector<LineVertex> &out) : out_(out) {}
    void line(const Vector3 &from, const Vector3 &to, const DebugColor &color) override {
        pushLine(out_, from.cast<float>(), to.cast<float>(), Rgb{color.r, color.g, color.b});
    }

private:
    std::vector<LineVertex> &out_;
};

}  // namespace

const GpuMesh &WorldView::meshOf(const World &world, BodyId id) {
    if (meshes_.size() <= id.index) meshes_.resize(id.index + 1);
    CachedMesh &cached = meshes_[id.index];
    if (!cached.valid || cached.generation != id.generation) {
        cached.mesh = GpuMesh(shapeMesh(world.shape(id), world.localCentreOfMass(id)));
        cached.generation = id.generation;
        cached.valid = true;
    }
    return cached.mesh;
}

void WorldView::clear() {
    meshes_.clear();
    unitCube_ = GpuMesh();
}

void WorldView::draw(Renderer &renderer, const Session &session, const ViewOptions &options) {
    const World &world = session.world();
    const FixedStepper &stepper = session.stepper();
    world.bodies(ids_);
    lines_.clear();
    overlay_.clear();

    for (BodyId id : ids_) {
        const Shape &shape = world.shape(id);
        const bool plane = shape.type == ShapeType::Plane;
        float model[16];
        stepper.glTransform(id, model);
        if (!std::isfinite(model[12]) || !std::isfinite(model[13]) || !std::isfinite(model[14])) continue;
        if (plane) {
            const PlaneAxes axes = planeAxes(shape);
            const GridAxes grid{axes.centre, axes.u / kGridSpacing, axes.v / kGridSpacing};
            renderer.drawGround(meshOf(world, id), model, kGroundColor, kGridColor, grid);
        } else if (options.solids && shape.type == ShapeType::Box) {
            // Every box is drawn from the cube of half sizes 1, scaled by its model matrix.
            if (unitCube_.indexCount() == 0) unitCube_ = GpuMesh(shapeMesh(Shape::box(Vector3::Ones())));
            const Rgb face = stateColor(session.state(id));
            const Rgb edge = options.edges ? Rgb{face.r * 0.4f, face.g * 0.4f, face.b * 0.4f} : face;
            const Eigen::Vector3f h = shape.halfExtents.cast<float>();
            for (int axis = 0; axis < 3; ++axis) {
                for (int row = 0; row < 3; ++row) model[4 * axis + row] *= h[axis];
            }
            renderer.drawBox(unitCube_, model, face, edge);
        } else if (options.solids) {
            renderer.drawMesh(meshOf(world, id), model, stateColor(session.state(id)), shape.type != ShapeType::Mesh);
        }
    }
    if (options.springs) {
        const std::vector<Vector3> springs = session.springLines();
        for (std::size_t i = 0; i + 1 < springs.size(); i += 2) {
            pushLine(lines_, springs[i].cast<float>(), springs[i + 1].cast<float>(), kSpringColor);
        }
    }
    renderer.drawLines(lines_, false);

    if (options.wireframes || options.contacts || options.boundingBoxes || options.joints) {
        DebugDrawOptions debug;
        debug.shapes = options.wireframes;
        debug.staticBodies = options.wireframes;
        debug.contacts = options.contacts;
        debug.joints = options.joints;
        debug.boundingBoxes = options.boundingBoxes;
        debug.planeHalfSize = kPlaneHalfSize;
        LineCollector collector(overlay_);
        world.debugDraw(collector, debug);
        renderer.drawLines(overlay_, true);
    }
}

}  // namespace cyclone::viewer
