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
const char *kMeshVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 model;
uniform mat4 viewProjection;
uniform vec3 color;
uniform vec3 eye;
uniform vec3 sky;
out vec3 shade;
void main() {
    vec4 p = model * vec4(position, 1.0);
    vec3 n = normalize(mat3(model) * normal);
    // Faces seen from behind (a mesh's back side) are lit as if turned towards the eye.
    if (dot(n, eye - p.xyz) < 0.0) n = -n;
    vec3 key = normalize(vec3(0.3, 0.8, 0.55));
    vec3 fill = normalize(vec3(-0.6, 0.3, -0.4));
    float hemisphere = 0.5 + 0.5 * n.y;
    float light = 0.22 + 0.18 * hemisphere + 0.62 * max(dot(n, key), 0.0) + 0.18 * max(dot(n, fill), 0.0);
    float fog = clamp((length(p.xyz - eye) - 60.0) / 140.0, 0.0, 0.7);
    shade = mix(color * light, sky, fog);
    gl_Position = viewProjection * p;
}
)";

const char *kMeshFragment = R"(#version 330 core
in vec3 shade;
out vec4 fragment;
void main() { fragment = vec4(shade, 1.0); }
)";

const char *kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;
uniform mat4 viewProjection;
out vec3 lineColor;
void main() {
    lineColor = color;
    gl_Position = viewProjection * vec4(position, 1.0);
}
)";

const char *kLineFragment = R"(#version 330 core
in vec3 lineColor;
out vec4 fragment;
void main() { fragment = vec4(lineColor, 1.0); }
)";

GLuint compile(GLenum type, const char *source) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
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

GLuint link(const char *vertexSource, const char *fragmentSource) {
    const GLuint vertex = compile(GL_VERTEX_SHADER, vertexSource);
    const GLuint fragment = compile(GL_FRAGMENT_SHADER, fragmentSource);
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
    meshProgram_ = link(kMeshVertex, kMeshFragment);
    lineProgram_ = link(kLineVertex, kLineFragment);
    meshModel_ = glGetUniformLocation(meshProgram_, "model");
    meshViewProjection_ = glGetUniformLocation(meshProgram_, "viewProjection");
    meshColor_ = glGetUniformLocation(meshProgram_, "color");
    meshEye_ = glGetUniformLocation(meshProgram_, "eye");
    meshSky_ = glGetUniformLocation(meshProgram_, "sky");
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
    glDeleteProgram(meshProgram_);
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
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(meshProgram_);
    glUniformMatrix4fv(meshViewProjection_, 1, GL_FALSE, viewProjection_.data());
    glUniform3f(meshEye_, eye_.x(), eye_.y(), eye_.z());
    glUniform3f(meshSky_, kSkyColor.r, kSkyColor.g, kSkyColor.b);
}

void Renderer::drawMesh(const GpuMesh &mesh, const float model[16], const Rgb &color, bool closed) {
    if (mesh.indexCount() == 0) return;
    if (closed != culling_) {
        if (closed) {
            glEnable(GL_CULL_FACE);
        } else {
            glDisable(GL_CULL_FACE);
        }
        culling_ = closed;
    }
    glUseProgram(meshProgram_);
    glUniformMatrix4fv(meshModel_, 1, GL_FALSE, model);
    glUniform3f(meshColor_, color.r, color.g, color.b);
    glBindVertexArray(mesh.vertexArray());
    glDrawElements(GL_TRIANGLES, mesh.indexCount(), GL_UNSIGNED_INT, nullptr);
}

void Renderer::drawLines(const std::vector<LineVertex> &vertices, bool onTop) {
    if (vertices.empty()) return;
    glUseProgram(lineProgram_);
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
