#include "world_view.h"

#include <cmath>

namespace cyclone::viewer {

namespace {

void pushLine(std::vector<LineVertex> &out, const Eigen::Vector3f &from, const Eigen::Vector3f &to, const Rgb &c) {
    out.push_back({{from.x(), from.y(), from.z()}, {c.r, c.g, c.b}});
    out.push_back({{to.x(), to.y(), to.z()}, {c.r, c.g, c.b}});
}

// The 12 edges of a box of half sizes `h` placed by `pose`.
void pushBoxEdges(std::vector<LineVertex> &out, const Eigen::Matrix4f &pose, const Eigen::Vector3f &h, const Rgb &c) {
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (float su : {-1.0f, 1.0f}) {
            for (float sv : {-1.0f, 1.0f}) {
                Eigen::Vector3f a, b;
                a[axis] = -h[axis];
                b[axis] = h[axis];
                a[u] = b[u] = su * h[u];
                a[v] = b[v] = sv * h[v];
                pushLine(out, (pose * a.homogeneous()).head<3>(), (pose * b.homogeneous()).head<3>(), c);
            }
        }
    }
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

void WorldView::clear() { meshes_.clear(); }

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
        if (options.solids || plane) {
            const bool closed = !plane && shape.type != ShapeType::Mesh;
            renderer.drawMesh(meshOf(world, id), model, plane ? kGroundColor : stateColor(session.state(id)), closed);
        }
        const Eigen::Map<const Eigen::Matrix4f> pose(model);
        if (options.solids && options.edges && shape.type == ShapeType::Box) {
            const Rgb face = stateColor(session.state(id));
            pushBoxEdges(lines_, pose, shape.halfExtents.cast<float>(), Rgb{face.r * 0.4f, face.g * 0.4f, face.b * 0.4f});
        }
        if (plane) {
            const std::vector<Eigen::Vector3f> grid = planeGridLines(shape);
            for (std::size_t i = 0; i + 1 < grid.size(); i += 2) {
                pushLine(lines_, (pose * grid[i].homogeneous()).head<3>(), (pose * grid[i + 1].homogeneous()).head<3>(),
                         kGridColor);
            }
        }
    }
    if (options.springs) {
        const std::vector<Vector3> springs = session.springLines();
        for (std::size_t i = 0; i + 1 < springs.size(); i += 2) {
            pushLine(lines_, springs[i].cast<float>(), springs[i + 1].cast<float>(), kSpringColor);
        }
    }
    renderer.drawLines(lines_, false);

    if (options.wireframes || options.contacts || options.boundingBoxes) {
        DebugDrawOptions debug;
        debug.shapes = options.wireframes;
        debug.staticBodies = options.wireframes;
        debug.contacts = options.contacts;
        debug.boundingBoxes = options.boundingBoxes;
        debug.planeHalfSize = kPlaneHalfSize;
        LineCollector collector(overlay_);
        world.debugDraw(collector, debug);
        renderer.drawLines(overlay_, true);
    }
}

}  // namespace cyclone::viewer
