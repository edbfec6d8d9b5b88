// Drawing with OpenGL 3.3 core: lit solid meshes (one draw per body; boxes with their
// edges and planes with their grid drawn by the fragment shader) and coloured lines (debug
// drawing, springs) batched into one draw per frame. Needs a current GL
// context from construction to destruction.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "gl.h"
#include "meshes.h"
#include "palette.h"

namespace cyclone::viewer {

/// A TriangleMesh in GL buffers. Move-only.
class GpuMesh {
public:
    GpuMesh() = default;
    explicit GpuMesh(const TriangleMesh &mesh);
    ~GpuMesh();
    GpuMesh(const GpuMesh &) = delete;
    GpuMesh &operator=(const GpuMesh &) = delete;
    GpuMesh(GpuMesh &&other) noexcept;
    GpuMesh &operator=(GpuMesh &&other) noexcept;

    GLuint vertexArray() const { return vertexArray_; }
    GLsizei indexCount() const { return indexCount_; }

private:
    void release();
    GLuint vertexArray_ = 0;
    GLuint buffers_[2] = {0, 0};
    GLsizei indexCount_ = 0;
};

/// A vertex of a line: world position (m) and colour.
struct LineVertex {
    float position[3];
    float color[3];
};

/// Where a plane's grid lines lie, in its body's frame: lines where the coordinates
/// (p - origin) . u and (p - origin) . v are whole numbers (u and v are the tangents divided
/// by the spacing of the lines).
struct GridAxes {
    Eigen::Vector3f origin = Eigen::Vector3f::Zero();
    Eigen::Vector3f u = Eigen::Vector3f::UnitX();
    Eigen::Vector3f v = Eigen::Vector3f::UnitZ();
};

/// The GL programs and per-frame state.
class Renderer {
public:
    /// Compiles the shaders; throws std::runtime_error with GL's log if they do not build.
    Renderer();
    ~Renderer();
    Renderer(const Renderer &) = delete;
    Renderer &operator=(const Renderer &) = delete;

    /// Clears a width x height picture to the sky colour and sets the camera for the
    /// draws that follow.
    void beginFrame(int width, int height, const Eigen::Matrix4f &viewProjection, const Eigen::Vector3f &eye);
    /// Draws `mesh` placed by `model` (column-major 4x4, body to world) in `color`, lit.
    /// A `closed` mesh (a solid's surface, counter-clockwise from outside) has its back
    /// faces culled: they are hidden anyway, and not rasterizing them is most of the
    /// saving on a software renderer. Open meshes and planes are drawn on both sides.
    void drawMesh(const GpuMesh &mesh, const float model[16], const Rgb &color, bool closed);
    /// Draws a box: `unitCube` (the box of half sizes 1) placed and scaled by `model`, lit,
    /// with a band about a pixel wide in `edgeColor` along the border of each face.
    void drawBox(const GpuMesh &unitCube, const float model[16], const Rgb &color, const Rgb &edgeColor);
    /// Draws a plane's mesh, lit, on both sides, with grid lines one pixel wide in
    /// `gridColor` where `grid` puts them.
    void drawGround(const GpuMesh &mesh, const float model[16], const Rgb &color, const Rgb &gridColor,
                    const GridAxes &grid);
    /// Draws line segments (pairs of vertices); `onTop` draws them over everything.
    void drawLines(const std::vector<LineVertex> &vertices, bool onTop);

private:
    /// The mesh shaders' variants: plain, box edges, plane grid.
    enum Surface { Plain, Edges, Grid, kSurfaces };
    struct MeshProgram {
        GLuint id = 0;
        GLint model = -1, viewProjection = -1, color = -1, eye = -1, sky = -1, lineColor = -1;
        GLint gridOrigin = -1, gridU = -1, gridV = -1;
    };
    const MeshProgram &use(int surface);
    void draw(int surface, const GpuMesh &mesh, const float model[16], const Rgb &color, bool closed);

    MeshProgram meshPrograms_[kSurfaces];
    int current_ = -1;  ///< The mesh program in use, -1 when none (or another program).
    GLuint lineProgram_ = 0;
    GLint lineViewProjection_ = -1;
    GLuint lineArray_ = 0, lineBuffer_ = 0;
    std::size_t lineCapacity_ = 0;
    bool culling_ = false;  // whether GL_CULL_FACE is on
    Eigen::Matrix4f viewProjection_ = Eigen::Matrix4f::Identity();
    Eigen::Vector3f eye_ = Eigen::Vector3f::Zero();
};

}  // namespace cyclone::viewer
