#include "render/GlObjects_p.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "render/GlError.h"
#include "render/ShaderSources.h"

namespace lucent {

void gl_delete::texture(GLuint name) {
    glDeleteTextures(1, &name);
}
void gl_delete::framebuffer(GLuint name) {
    glDeleteFramebuffers(1, &name);
}
void gl_delete::vertexArray(GLuint name) {
    glDeleteVertexArrays(1, &name);
}
void gl_delete::program(GLuint name) {
    glDeleteProgram(name);
}
void gl_delete::buffer(GLuint name) {
    glDeleteBuffers(1, &name);
}

GlTexture makeTexture2D(GLenum format, int width, int height) {
    GlTexture texture = makeTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.get(), 1, format, width, height);
    return texture;
}

GlTexture makeTexture3D(GLenum format, glm::ivec3 size, GLenum clientFormat, GLenum type,
                        const void* data) {
    GlTexture t = makeTexture(GL_TEXTURE_3D);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1); // rows of one-byte codes are not 4-aligned
    glTextureStorage3D(t.get(), 1, format, size.x, size.y, size.z);
    glTextureSubImage3D(t.get(), 0, 0, 0, 0, size.x, size.y, size.z, clientFormat, type, data);
    return t;
}

GlFramebuffer makeFramebuffer(std::initializer_list<std::pair<GLenum, GLuint>> attachments,
                              const std::string& what) {
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    GlFramebuffer framebuffer(name);
    std::vector<GLenum> drawn;
    for (const auto& [point, texture] : attachments) {
        glNamedFramebufferTexture(name, point, texture, 0);
        if (point != GL_DEPTH_ATTACHMENT) {
            drawn.push_back(point);
        }
    }
    glNamedFramebufferDrawBuffers(name, GLsizei(drawn.size()), drawn.data());
    if (glCheckNamedFramebufferStatus(name, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw GlError("the " + what + " framebuffer is not complete on this driver");
    }
    checkGl(what + " framebuffer");
    return framebuffer;
}

GlTexture makeTexture(GLenum target) {
    GLuint name = 0;
    glCreateTextures(target, 1, &name);
    // Nearest by default: integer textures are incomplete (read as zero) with
    // any other filter, and tables are interpolated by the shader itself.
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return GlTexture(name);
}

namespace {

// The shader's text with each line `#include "name"` replaced by that embedded file's text
// (one level: an included file includes nothing).
std::string withIncludes(std::string_view fileName) {
    std::string text(shaderSource(fileName));
    const std::string directive = "#include \"";
    for (std::size_t at = text.find(directive); at != std::string::npos;
         at = text.find(directive, at)) {
        const std::size_t nameEnd = text.find('"', at + directive.size());
        const std::size_t lineEnd = text.find('\n', at);
        const std::string name =
            text.substr(at + directive.size(), nameEnd - at - directive.size());
        const std::string included(shaderSource(name));
        text.replace(at, (lineEnd == std::string::npos ? text.size() : lineEnd) - at, included);
        at += included.size();
    }
    return text;
}

GLuint compile(GLenum stage, std::string_view fileName, const std::string& defines) {
    std::string text = withIncludes(fileName);
    const std::size_t lineEnd = text.find('\n');
    text.insert(lineEnd == std::string::npos ? text.size() : lineEnd + 1, defines);
    const GLuint shader = glCreateShader(stage);
    const char* source = text.data();
    const GLint length = GLint(text.size());
    glShaderSource(shader, 1, &source, &length);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        GLint size = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &size);
        std::string log(std::size_t(std::max(size, 1)), '\0');
        glGetShaderInfoLog(shader, size, nullptr, log.data());
        glDeleteShader(shader);
        throw GlError("shader " + std::string(fileName) + " does not compile: " + log);
    }
    return shader;
}

} // namespace

ShaderProgram::ShaderProgram(std::string_view vertexName, std::string_view fragmentName,
                             const std::string& defines) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vertexName, defines);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, fragmentName, defines);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    program_ = GlName<gl_delete::program>(glCreateProgram());
    glAttachShader(program_.get(), vs);
    glAttachShader(program_.get(), fs);
    glLinkProgram(program_.get());
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(program_.get(), GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        GLint size = 0;
        glGetProgramiv(program_.get(), GL_INFO_LOG_LENGTH, &size);
        std::string log(std::size_t(std::max(size, 1)), '\0');
        glGetProgramInfoLog(program_.get(), size, nullptr, log.data());
        throw GlError("shaders " + std::string(vertexName) + " + " + std::string(fragmentName) +
                      " do not link: " + log);
    }
}

void checkGl(const std::string& what) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) {
        return;
    }
    while (glGetError() != GL_NO_ERROR) {
    }
    if (e == GL_OUT_OF_MEMORY) {
        throw GlOutOfMemory(what + ": the driver is out of memory");
    }
    throw GlError(what + ": GL error 0x" + [&] {
        char buf[16];
        std::snprintf(buf, sizeof buf, "%04x", unsigned(e));
        return std::string(buf);
    }());
}

} // namespace lucent
