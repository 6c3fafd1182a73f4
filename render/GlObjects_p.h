#pragma once
// Owning handles for GL objects and a linked shader program. Private to render/:
// epoxy's GL header stays out of the public headers.

#include <epoxy/gl.h>

#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

#include <glm/glm.hpp>

namespace lucent {

// One GL name, deleted with its owner. Needs the context that made it current.
template <void (*Delete)(GLuint)> class GlName {
public:
    GlName() = default;
    explicit GlName(GLuint name) : name_(name) {}
    ~GlName() { reset(); }
    GlName(GlName&& o) noexcept : name_(std::exchange(o.name_, 0)) {}
    GlName& operator=(GlName&& o) noexcept {
        if (this != &o) {
            reset();
            name_ = std::exchange(o.name_, 0);
        }
        return *this;
    }
    GlName(const GlName&) = delete;
    GlName& operator=(const GlName&) = delete;
    GLuint get() const { return name_; }
    void reset() {
        if (name_ != 0) {
            Delete(name_);
            name_ = 0;
        }
    }

private:
    GLuint name_ = 0;
};

namespace gl_delete {
void texture(GLuint name);
void framebuffer(GLuint name);
void vertexArray(GLuint name);
void program(GLuint name);
void buffer(GLuint name);
} // namespace gl_delete

using GlTexture = GlName<gl_delete::texture>;
using GlFramebuffer = GlName<gl_delete::framebuffer>;
using GlVertexArray = GlName<gl_delete::vertexArray>;
using GlBuffer = GlName<gl_delete::buffer>;

GlTexture makeTexture(GLenum target);
// A 2D texture with immutable storage of `format` (makeTexture's filtering).
GlTexture makeTexture2D(GLenum format, int width, int height);
// A 3D texture with immutable storage of `format`, filled from `data` (rows of
// `clientFormat`/`type`, tightly packed), with makeTexture's filtering.
GlTexture makeTexture3D(GLenum format, glm::ivec3 size, GLenum clientFormat, GLenum type,
                        const void* data);
// A framebuffer of these (attachment point, texture) pairs that draws into
// its colour attachments in the order given. Throws GlError saying "the
// <what> framebuffer is not complete on this driver" when the driver refuses.
GlFramebuffer makeFramebuffer(std::initializer_list<std::pair<GLenum, GLuint>> attachments,
                              const std::string& what);

// A vertex and a fragment shader linked into one program. Throws GlError with
// the driver's log (and the shader's name) when either fails.
class ShaderProgram {
public:
    // defines: lines inserted after each shader's #version line.
    ShaderProgram(std::string_view vertexName, std::string_view fragmentName,
                  const std::string& defines = {});
    void use() const { glUseProgram(program_.get()); }
    GLint location(const char* name) const { return glGetUniformLocation(program_.get(), name); }

    void set(const char* name, int v) const { glUniform1i(location(name), v); }
    void set(const char* name, bool v) const { glUniform1i(location(name), v ? 1 : 0); }
    void set(const char* name, float v) const { glUniform1f(location(name), v); }
    void set(const char* name, double v) const { glUniform1d(location(name), v); }
    void set(const char* name, glm::ivec2 v) const { glUniform2i(location(name), v.x, v.y); }
    void set(const char* name, glm::ivec3 v) const { glUniform3i(location(name), v.x, v.y, v.z); }
    void set(const char* name, glm::vec3 v) const { glUniform3f(location(name), v.x, v.y, v.z); }
    void set(const char* name, glm::vec4 v) const {
        glUniform4f(location(name), v.x, v.y, v.z, v.w);
    }
    void set(const char* name, glm::dvec3 v) const { glUniform3d(location(name), v.x, v.y, v.z); }
    void set(const char* name, const glm::mat3& m) const {
        glUniformMatrix3fv(location(name), 1, GL_FALSE, &m[0][0]);
    }
    void set(const char* name, const glm::dmat3& m) const {
        glUniformMatrix3dv(location(name), 1, GL_FALSE, &m[0][0]);
    }

private:
    GlName<gl_delete::program> program_;
};

// Throws GlError naming `what` when the GL error flag is set (GL_OUT_OF_MEMORY
// says so plainly).
void checkGl(const std::string& what);

} // namespace lucent
