#include "render/SurfaceRenderer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/image/ColourMap.h"
#include "core/surface/VertexNormals.h"
#include "render/GlError.h"
#include "render/GlObjects_p.h"

namespace lucent {
namespace {

constexpr int kColourMapSize = 1024;
// The near plane no closer than this share of the far one (where the eye is
// inside the mesh's bounding sphere): a 32-bit float depth buffer then still
// orders surfaces a few hundredths of a millimetre apart at 500 mm. Parts of
// the mesh nearer than that to the eye are clipped.
constexpr double kNearShare = 1e-3;

static_assert(sizeof(glm::u32vec3) == 3 * sizeof(std::uint32_t), "triangles upload as they are");

GlBuffer makeBuffer(const void* data, std::size_t bytes) {
    GLuint name = 0;
    glCreateBuffers(1, &name);
    GlBuffer buffer(name);
    glNamedBufferStorage(name, GLsizeiptr(bytes), data, 0);
    return buffer;
}

} // namespace

void checkSurfaceDisplay(const SurfaceDisplay& display) {
    if (!display.mesh) {
        return;
    }
    const TriangleMesh& mesh = *display.mesh;
    const std::size_t vertices = mesh.vertices.size();
    if (mesh.triangles.size() > std::size_t(std::numeric_limits<int>::max() / 3)) {
        throw std::invalid_argument(
            "the surface has " + std::to_string(mesh.triangles.size()) + " triangles; at most " +
            std::to_string(std::numeric_limits<int>::max() / 3) + " can be drawn");
    }
    for (const glm::u32vec3& t : mesh.triangles) {
        const std::uint32_t most = std::max({t.x, t.y, t.z});
        if (most >= vertices) {
            throw std::invalid_argument("a triangle of the surface names vertex " +
                                        std::to_string(most) + "; the mesh has " +
                                        std::to_string(vertices) + " vertices");
        }
    }
    if (display.field && display.field->size() != vertices) {
        throw std::invalid_argument(
            "the surface's field has " + std::to_string(display.field->size()) +
            " values for a mesh of " + std::to_string(vertices) + " vertices");
    }
}

struct SurfaceRenderer::Gl {
    ShaderProgram program{"surface.vert", "surface.frag"};
    GlVertexArray vao;
    GlTexture colourMap;
    GlBuffer vertices, indices, field;
    // What the buffers hold: weak, so that a display dropped frees its mesh.
    std::weak_ptr<const TriangleMesh> uploadedMesh;
    std::weak_ptr<const std::vector<float>> uploadedField;
    glm::dvec3 centre{0.0};
    double radius = 0.0;
    int indexCount = 0;

    int width = 0, height = 0;
    GlFramebuffer framebuffer;
    GlTexture colour, distance, depth;

    void resize(int w, int h);
    std::size_t upload(const SurfaceDisplay& display);
};

SurfaceRenderer::SurfaceRenderer() : gl_(std::make_unique<Gl>()) {
    Gl& g = *gl_;
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    g.vao = GlVertexArray(vao);
    // Binding 0: position and normal interleaved; binding 1: the field.
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float));
    glVertexArrayAttribFormat(vao, 2, 1, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    glVertexArrayAttribBinding(vao, 1, 0);
    glVertexArrayAttribBinding(vao, 2, 1);
    glEnableVertexArrayAttrib(vao, 0);
    glEnableVertexArrayAttrib(vao, 1);

    std::vector<glm::vec4> map(kColourMapSize);
    for (int i = 0; i < kColourMapSize; ++i) {
        map[std::size_t(i)] = glm::vec4(glm::vec3(viridis(double(i) / (kColourMapSize - 1))), 1.0f);
    }
    g.colourMap = makeTexture(GL_TEXTURE_1D);
    const GLuint m = g.colourMap.get();
    glTextureStorage1D(m, 1, GL_RGBA32F, kColourMapSize);
    glTextureSubImage1D(m, 0, 0, kColourMapSize, GL_RGBA, GL_FLOAT, map.data());
    glTextureParameteri(m, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(m, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(m, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    checkGl("surface renderer setup");
}

SurfaceRenderer::~SurfaceRenderer() = default;

unsigned SurfaceRenderer::colour() const {
    return gl_->colour.get();
}

unsigned SurfaceRenderer::distance() const {
    return gl_->distance.get();
}

void SurfaceRenderer::Gl::resize(int w, int h) {
    if (w == width && h == height && framebuffer.get() != 0) {
        return;
    }
    colour = makeTexture2D(GL_RGBA32F, w, h);
    distance = makeTexture2D(GL_R32F, w, h);
    depth = makeTexture2D(GL_DEPTH_COMPONENT32F, w, h);
    framebuffer = makeFramebuffer({{GL_COLOR_ATTACHMENT0, colour.get()},
                                   {GL_COLOR_ATTACHMENT1, distance.get()},
                                   {GL_DEPTH_ATTACHMENT, depth.get()}},
                                  std::to_string(w) + "x" + std::to_string(h) + " surface");
    width = w;
    height = h;
}

std::size_t SurfaceRenderer::Gl::upload(const SurfaceDisplay& display) {
    std::size_t bytes = 0;
    // A weak pointer that still locks to the display's is the same live mesh
    // (a freed one's address may be reused; then it no longer locks).
    if (!display.mesh) {
        uploadedMesh.reset();
        indexCount = 0;
    } else if (uploadedMesh.lock() != display.mesh) {
        const TriangleMesh& mesh = *display.mesh;
        glm::dvec3 lo(std::numeric_limits<double>::max()),
            hi(std::numeric_limits<double>::lowest());
        for (const glm::dvec3& v : mesh.vertices) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        centre = mesh.vertices.empty() ? glm::dvec3(0.0) : 0.5 * (lo + hi);
        radius = 0.0;
        for (const glm::dvec3& v : mesh.vertices) {
            radius = std::max(radius, glm::length(v - centre));
        }
        indexCount = 0;
        if (!mesh.triangles.empty()) {
            const std::vector<glm::dvec3> normals = vertexNormals(mesh);
            std::vector<float> interleaved;
            interleaved.reserve(6 * mesh.vertices.size());
            for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
                const glm::vec3 p(mesh.vertices[i] - centre), n(normals[i]);
                interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
            }
            const std::size_t vertexBytes = interleaved.size() * sizeof(float);
            const std::size_t indexBytes = mesh.triangles.size() * sizeof(glm::u32vec3);
            vertices = makeBuffer(interleaved.data(), vertexBytes);
            indices = makeBuffer(mesh.triangles.data(), indexBytes);
            glVertexArrayVertexBuffer(vao.get(), 0, vertices.get(), 0, 6 * sizeof(float));
            glVertexArrayElementBuffer(vao.get(), indices.get());
            indexCount = int(3 * mesh.triangles.size());
            bytes += vertexBytes + indexBytes;
        }
        uploadedMesh = display.mesh;
    }
    if (!display.field) {
        uploadedField.reset();
        glDisableVertexArrayAttrib(vao.get(), 2);
    } else if (uploadedField.lock() != display.field) {
        // NaN takes the low end, as viridis() gives it.
        std::vector<float> values(*display.field);
        std::replace_if(
            values.begin(), values.end(), [](float f) { return std::isnan(f); },
            std::numeric_limits<float>::lowest());
        if (!values.empty()) {
            field = makeBuffer(values.data(), values.size() * sizeof(float));
            glVertexArrayVertexBuffer(vao.get(), 1, field.get(), 0, sizeof(float));
            bytes += values.size() * sizeof(float);
        }
        glEnableVertexArrayAttrib(vao.get(), 2);
        uploadedField = display.field;
    }
    checkGl("uploading the surface");
    return bytes;
}

std::size_t SurfaceRenderer::draw(const SurfaceDisplay& display, const ViewFrame& frame,
                                  const Shading& light, int width, int height) {
    Gl& g = *gl_;
    g.resize(width, height);
    const std::size_t bytes = g.upload(display);
    const GLuint fb = g.framebuffer.get();
    glBindFramebuffer(GL_FRAMEBUFFER, fb);
    glViewport(0, 0, width, height);
    // Whatever the context's owner left set that would clip, blend or cull.
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE); // back faces stop rays too
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    const GLfloat transparent[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const GLfloat none[4] = {std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 0.0f};
    const GLfloat farthest = 1.0f;
    glClearNamedFramebufferfv(fb, GL_COLOR, 0, transparent);
    glClearNamedFramebufferfv(fb, GL_COLOR, 1, none);
    glClearNamedFramebufferfv(fb, GL_DEPTH, 0, &farthest);

    // Near and far planes around the mesh's bounding sphere, a little wider.
    const glm::dvec3 eye = frame.eye - g.centre;
    const double middle = -glm::dot(eye, frame.forward);
    const double margin = 0.01 * g.radius + 1e-3;
    const double farZ = middle + g.radius + margin;
    if (g.indexCount > 0 && farZ > 0.0) {
        const double nearZ = std::max(middle - g.radius - margin, kNearShare * farZ);
        const ShaderProgram& p = g.program;
        p.use();
        p.set("uEye", glm::vec3(eye));
        p.set("uView",
              glm::mat3(glm::transpose(glm::dmat3(frame.right, frame.up, -frame.forward))));
        p.set("uProjection",
              glm::vec4(float(1.0 / (frame.tanHalfFov * frame.aspect)),
                        float(1.0 / frame.tanHalfFov), float(-(farZ + nearZ) / (farZ - nearZ)),
                        float(-2.0 * farZ * nearZ / (farZ - nearZ))));
        p.set("uLight",
              glm::vec4(light.ambient, light.diffuse, light.specular, light.specularPower));
        p.set("uUseField", display.field != nullptr);
        p.set("uColour", glm::vec3(display.colour));
        // As viridisBytes: the middle of the map when the range is empty.
        const bool range = display.fieldHi > display.fieldLo;
        p.set("uFieldLo", float(display.fieldLo));
        p.set("uFieldScale", range ? float(1.0 / (display.fieldHi - display.fieldLo)) : 0.0f);
        p.set("uFieldOffset", range ? 0.0f : 0.5f);
        p.set("uColourMap", 0);
        p.set("uColourMapSize", kColourMapSize);
        glBindTextureUnit(0, g.colourMap.get());
        glBindSampler(0, 0);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glBindVertexArray(g.vao.get());
        glDrawElements(GL_TRIANGLES, g.indexCount, GL_UNSIGNED_INT, nullptr);
        glBindVertexArray(0);
        glBindTextureUnit(0, 0);
        glUseProgram(0);
        glDisable(GL_DEPTH_TEST);
    }
    checkGl("drawing the surface");
    return bytes;
}

void SurfaceRenderer::copyColourTo(unsigned texture) const {
    glCopyImageSubData(gl_->colour.get(), GL_TEXTURE_2D, 0, 0, 0, 0, texture, GL_TEXTURE_2D, 0, 0,
                       0, 0, gl_->width, gl_->height, 1);
    checkGl("copying the surface's colour");
}

} // namespace lucent
