// The picture of a Session's World: each body's shape as a lit mesh coloured by its state,
// planes with a grid, springs, and the World's own debug drawing (wireframes, contacts,
// broadphase boxes) on top.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer.h"
#include "session.h"

namespace cyclone::viewer {

/// What is drawn; the overlay's check boxes.
struct ViewOptions {
    /// Lit solid shapes.
    bool solids = true;
    /// The edges of boxes, darker than their faces (a pile of boxes reads as boxes).
    bool edges = true;
    /// The World's wireframes of the shapes (DebugDrawOptions::shapes).
    bool wireframes = false;
    /// Contact points and normals (DebugDrawOptions::contacts).
    bool contacts = false;
    /// Broadphase boxes (DebugDrawOptions::boundingBoxes).
    bool boundingBoxes = false;
    /// Joints' anchors, axes and limits (DebugDrawOptions::joints).
    bool joints = true;
    /// The scene's springs and the mouse's, as lines.
    bool springs = true;
};

/// Draws a Session's World, keeping one GPU mesh per body.
class WorldView {
public:
    /// Draws the bodies where the session's FixedStepper shows them (interpolated), then
    /// the lines `options` asks for.
    void draw(Renderer &renderer, const Session &session, const ViewOptions &options);
    /// Forgets the meshes: call it when the World is rebuilt or replaced, since a new
    /// World reuses body handles for other shapes.
    void clear();

private:
    struct CachedMesh {
        std::uint32_t generation = 0;
        bool valid = false;
        GpuMesh mesh;
    };
    const GpuMesh &meshOf(const World &world, BodyId id);

    std::vector<CachedMesh> meshes_;  ///< By BodyId::index; boxes use unitCube_.
    GpuMesh unitCube_;                ///< Every box's mesh: the cube of half sizes 1.
    std::vector<BodyId> ids_;
    std::vector<LineVertex> lines_;     ///< Drawn with depth: springs.
    std::vector<LineVertex> overlay_;   ///< Drawn on top: the World's debug drawing.
};

}  // namespace cyclone::viewer
