#include "renderer.h"

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace cyclone::viewer {

namespace {

// Lambert lighting from a key light and a fill light, a hemisphere ambient term and a
// touch of distance fog towards the sky, so that depth reads without shadows. Lit per
// vertex: Mesa's software renderer spends most of a frame shading fragments, and the
// shapes' faces are flat or finely divided, so per-pixel lighting would look the same.
// The vertex shader also hands on the fog and the position in the mesh's own frame, from
// which two fragment shaders draw lines without line primitives (a software renderer sets
// up and bins each line on its own, and the ground's grid crosses the whole picture):
// EDGES darkens a band about one pixel wide along the border of each face of a unit cube
// (a box scaled by its model matrix), GRID draws the lines of a plane's grid.
const char *kMeshVertex = R"(
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 model;
uniform mat4 viewProjection;
uniform vec3 color;
uniform vec3 eye;
uniform vec3 sky;
uniform vec3 gridOrigin;
uniform vec3 gridU;
uniform vec3 gridV;
out vec3 shade;
out float fog;
out vec3 local;
out vec3 across;
out vec2 grid;
void main() {
    vec4 p = model * vec4(position, 1.0);
    vec3 n = normalize(mat3(model) * normal);
    // Faces seen from behind (a mesh's back side) are lit as if turned towards the eye.
    if (dot(n, eye - p.xyz) < 0.0) n = -n;
    vec3 key = normalize(vec3(0.3, 0.8, 0.55));
    vec3 fill = normalize(vec3(-0.6, 0.3, -0.4));
    float hemisphere = 0.5 + 0.5 * n.y;
    float light = 0.22 + 0.18 * hemisphere + 0.62 * max(dot(n, key), 0.0) + 0.18 * max(dot(n, fill), 0.0);
    fog = clamp((length(p.xyz - eye) - 60.0) / 140.0, 0.0, 0.7);
    shade = mix(color * light, sky, fog);
    local = position;
    across = abs(normal);
    grid = vec2(dot(position - gridOrigin, gridU), dot(position - gridOrigin, gridV));
    gl_Position = viewProjection * p;
}
)";

const char *kMeshFragment = R"(
in vec3 shade;
in float fog;
in vec3 local;
in vec3 across;
in vec2 grid;
uniform vec3 lineColor;
uniform vec3 sky;
out vec4 fragment;
void main() {
#if defined(EDGES)
    // Pixels to the face's border along each axis in the face; the axis across the face
    // (|local| = 1 all over it) is left out.
    vec3 toBorder = (1.0 - abs(local)) / max(fwidth(local), vec3(1e-6)) + across * 1e6;
    float cover = 1.0 - clamp(min(toBorder.x, min(toBorder.y, toBorder.z)) - 0.25, 0.0, 1.0);
#elif defined(GRID)
    // Pixels to the nearest grid line along each axis: a line one pixel wide, faded to
    // its mean cover where the lines are closer than a few pixels (towards the horizon).
    vec2 perPixel = max(fwidth(grid), vec2(1e-6));
    vec2 toLine = abs(fract(grid + 0.5) - 0.5) / perPixel;
    float cover = 1.0 - clamp(min(toLine.x, toLine.y), 0.0, 1.0);
    cover = mix(cover, min(perPixel.x + perPixel.y, 1.0), smoothstep(0.2, 0.5, max(perPixel.x, perPixel.y)));
#else
    float cover = 0.0;
#endif
    fragment = vec4(mix(shade, mix(lineColor, sky, fog), cover), 1.0);
}
)";

const char *kLineVertex = R"(
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;
uniform mat4 viewProjection;
out vec3 lineColor;
void main() {
    lineColor = color;
    gl_Position = viewProjection * vec4(position, 1.0);
}
)";

const char *kLineFragment = R"(
in vec3 lineColor;
out vec4 fragment;
void main() { fragment = vec4(lineColor, 1.0); }
)";

GLuint compile(GLenum type, const char *source, const char *defines) {
    const GLuint shader = glCreateShader(type);
    const char *parts[3] = {"#version 330 core\n", defines, source};
    glShaderSource(shader, 3, parts, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        char log[2048] = {0};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw std::runtime_error(std::string("cyclone-viewer: a shader did not compile: ") + log);
    }
    return shader;
}

GLuint link(const char *vertexSource, const char *fragmentSource, const char *defines = "") {
    const GLuint vertex = compile(GL_VERTEX_SHADER, vertexSource, defines);
    const GLuint fragment = compile(GL_FRAGMENT_SHADER, fragmentSource, defines);
    const GLuint program = glCreateProgram();
    glAttachShader(program, vertex);
    glAttachShader(program, fragment);
    glLinkProgram(program);
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        char log[2048] = {0};
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        glDeleteProgram(program);
        throw std::runtime_error(std::string("cyclone-viewer: a shader program did not link: ") + log);
    }
    return program;
}

// Attribute `index` of `components` floats at `offset` bytes in a vertex of `stride` bytes.
void floatAttribute(GLuint index, GLint components, GLsizei stride, std::size_t offset) {
    glEnableVertexAttribArray(index);
    glVertexAttribPointer(index, components, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void *>(offset));
}

}  // namespace

GpuMesh::GpuMesh(const TriangleMesh &mesh) : indexCount_(static_cast<GLsizei>(mesh.indices.size())) {
    glGenVertexArrays(1, &vertexArray_);
    glGenBuffers(2, buffers_);
    glBindVertexArray(vertexArray_);
    glBindBuffer(GL_ARRAY_BUFFER, buffers_[0]);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(MeshVertex)),
                 mesh.vertices.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers_[1]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                 mesh.indices.data(), GL_STATIC_DRAW);
    floatAttribute(0, 3, sizeof(MeshVertex), offsetof(MeshVertex, position));
    floatAttribute(1, 3, sizeof(MeshVertex), offsetof(MeshVertex, normal));
    glBindVertexArray(0);
}

GpuMesh::~GpuMesh() { release(); }

GpuMesh::GpuMesh(GpuMesh &&other) noexcept
    : vertexArray_(std::exchange(other.vertexArray_, 0)), indexCount_(std::exchange(other.indexCount_, 0)) {
    buffers_[0] = std::exchange(other.buffers_[0], 0);
    buffers_[1] = std::exchange(other.buffers_[1], 0);
}

GpuMesh &GpuMesh::operator=(GpuMesh &&other) noexcept {
    if (this != &other) {
        release();
        vertexArray_ = std::exchange(other.vertexArray_, 0);
        indexCount_ = std::exchange(other.indexCount_, 0);
        buffers_[0] = std::exchange(other.buffers_[0], 0);
        buffers_[1] = std::exchange(other.buffers_[1], 0);
    }
    return *this;
}

void GpuMesh::release() {
    if (vertexArray_ != 0) {
        glDeleteBuffers(2, buffers_);
        glDeleteVertexArrays(1, &vertexArray_);
    }
    vertexArray_ = 0;
    buffers_[0] = buffers_[1] = 0;
    indexCount_ = 0;
}

Renderer::Renderer() {
    const char *defines[kSurfaces] = {"", "#define EDGES\n", "#define GRID\n"};
    for (int i = 0; i < kSurfaces; ++i) {
        MeshProgram &program = meshPrograms_[i];
        program.id = link(kMeshVertex, kMeshFragment, defines[i]);
        program.model = glGetUniformLocation(program.id, "model");
        program.viewProjection = glGetUniformLocation(program.id, "viewProjection");
        program.color = glGetUniformLocation(program.id, "color");
        program.eye = glGetUniformLocation(program.id, "eye");
        program.sky = glGetUniformLocation(program.id, "sky");
        program.lineColor = glGetUniformLocation(program.id, "lineColor");
        program.gridOrigin = glGetUniformLocation(program.id, "gridOrigin");
        program.gridU = glGetUniformLocation(program.id, "gridU");
        program.gridV = glGetUniformLocation(program.id, "gridV");
    }
    lineProgram_ = link(kLineVertex, kLineFragment);
    lineViewProjection_ = glGetUniformLocation(lineProgram_, "viewProjection");
    glGenVertexArrays(1, &lineArray_);
    glGenBuffers(1, &lineBuffer_);
    glBindVertexArray(lineArray_);
    glBindBuffer(GL_ARRAY_BUFFER, lineBuffer_);
    floatAttribute(0, 3, sizeof(LineVertex), offsetof(LineVertex, position));
    floatAttribute(1, 3, sizeof(LineVertex), offsetof(LineVertex, color));
    glBindVertexArray(0);
}

Renderer::~Renderer() {
    glDeleteBuffers(1, &lineBuffer_);
    glDeleteVertexArrays(1, &lineArray_);
    glDeleteProgram(lineProgram_);
    for (const MeshProgram &program : meshPrograms_) glDeleteProgram(program.id);
}

void Renderer::beginFrame(int width, int height, const Eigen::Matrix4f &viewProjection, const Eigen::Vector3f &eye) {
    viewProjection_ = viewProjection;
    eye_ = eye;
    glViewport(0, 0, width, height);
    glClearColor(kSkyColor.r, kSkyColor.g, kSkyColor.b, 1);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDisable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    culling_ = false;
    // Solids a little behind their depth, so that the lines on their edges win.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1, 1);
    // The stencil is cleared with the depth although nothing uses it: the depth buffer
    // holds depth and stencil in one word, and Mesa's software renderer fills whole words
    // (a plain memset) instead of masking the stencil bits out of each one.
    glClearStencil(0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    for (const MeshProgram &program : meshPrograms_) {
        glUseProgram(program.id);
        glUniformMatrix4fv(program.viewProjection, 1, GL_FALSE, viewProjection_.data());
        glUniform3f(program.eye, eye_.x(), eye_.y(), eye_.z());
        glUniform3f(program.sky, kSkyColor.r, kSkyColor.g, kSkyColor.b);
    }
    current_ = -1;
}

void Renderer::drawMesh(const GpuMesh &mesh, const float model[16], const Rgb &color, bool closed) {
    draw(Plain, mesh, model, color, closed);
}

void Renderer::drawBox(const GpuMesh &unitCube, const float model[16], const Rgb &color, const Rgb &edgeColor) {
    const MeshProgram &program = use(Edges);
    glUniform3f(program.lineColor, edgeColor.r, edgeColor.g, edgeColor.b);
    draw(Edges, unitCube, model, color, true);
}

void Renderer::drawGround(const GpuMesh &mesh, const float model[16], const Rgb &color, const Rgb &gridColor,
                          const GridAxes &grid) {
    const MeshProgram &program = use(Grid);
    glUniform3f(program.lineColor, gridColor.r, gridColor.g, gridColor.b);
    glUniform3fv(program.gridOrigin, 1, grid.origin.data());
    glUniform3fv(program.gridU, 1, grid.u.data());
    glUniform3fv(program.gridV, 1, grid.v.data());
    draw(Grid, mesh, model, color, false);
}

const Renderer::MeshProgram &Renderer::use(int surface) {
    if (current_ != surface) {
        glUseProgram(meshPrograms_[surface].id);
        current_ = surface;
    }
    return meshPrograms_[surface];
}

void Renderer::draw(int surface, const GpuMesh &mesh, const float model[16], const Rgb &color, bool closed) {
    if (mesh.indexCount() == 0) return;
    if (closed != culling_) {
        if (closed) {
            glEnable(GL_CULL_FACE);
        } else {
            glDisable(GL_CULL_FACE);
        }
        culling_ = closed;
    }
    const MeshProgram &program = use(surface);
    glUniformMatrix4fv(program.model, 1, GL_FALSE, model);
    glUniform3f(program.color, color.r, color.g, color.b);
    glBindVertexArray(mesh.vertexArray());
    glDrawElements(GL_TRIANGLES, mesh.indexCount(), GL_UNSIGNED_INT, nullptr);
}

void Renderer::drawLines(const std::vector<LineVertex> &vertices, bool onTop) {
    if (vertices.empty()) return;
    glUseProgram(lineProgram_);
    current_ = -1;
    glUniformMatrix4fv(lineViewProjection_, 1, GL_FALSE, viewProjection_.data());
    glBindVertexArray(lineArray_);
    glBindBuffer(GL_ARRAY_BUFFER, lineBuffer_);
    const std::size_t bytes = vertices.size() * sizeof(LineVertex);
    if (bytes > lineCapacity_) {
        lineCapacity_ = bytes * 2;
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(lineCapacity_), nullptr, GL_STREAM_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), vertices.data());
    if (onTop) glDisable(GL_DEPTH_TEST);
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(vertices.size()));
    if (onTop) glEnable(GL_DEPTH_TEST);
    glBindVertexArray(0);
}

}  // namespace cyclone::viewer
