#include "render/OffscreenContext.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <map>
#include <mutex>
#include <string_view>
#include <vector>

#include "render/GlError.h"

namespace lucent {

namespace {

// An EGL display is one per process and eglInitialize does not count: the
// first eglTerminate would end every other context on it. So contexts count
// their display's users, and the last one terminates it.
std::mutex displayUsersMutex;
std::map<EGLDisplay, int> displayUsers;

void useDisplay(EGLDisplay display) {
    const std::lock_guard lock(displayUsersMutex);
    ++displayUsers[display];
}

void releaseDisplay(EGLDisplay display) {
    const std::lock_guard lock(displayUsersMutex);
    if (--displayUsers[display] <= 0) {
        displayUsers.erase(display);
        eglTerminate(display);
    }
}

} // namespace

struct OffscreenContext::Egl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    ~Egl() {
        if (display == EGL_NO_DISPLAY) {
            return;
        }
        // Another context current on this thread stays current.
        if (context != EGL_NO_CONTEXT && eglGetCurrentContext() == context) {
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        }
        if (context != EGL_NO_CONTEXT) {
            eglDestroyContext(display, context);
        }
        releaseDisplay(display);
    }
};

namespace {

bool hasExtension(const char* list, std::string_view name) {
    if (list == nullptr) {
        return false;
    }
    const std::string_view all(list);
    for (std::size_t at = all.find(name); at != std::string_view::npos;
         at = all.find(name, at + 1)) {
        const std::size_t end = at + name.size();
        if ((at == 0 || all[at - 1] == ' ') && (end == all.size() || all[end] == ' ')) {
            return true;
        }
    }
    return false;
}

// The displays worth trying, best first: the preferred EGL device (when one
// is asked for), surfaceless Mesa, then each EGL device (headless NVIDIA),
// then the default display.
std::vector<EGLDisplay> candidateDisplays(int preferred) {
    std::vector<EGLDisplay> out;
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (preferred >= 0 && hasExtension(clientExtensions, "EGL_EXT_platform_device") &&
        hasExtension(clientExtensions, "EGL_EXT_device_enumeration")) {
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        if (eglQueryDevicesEXT(8, devices, &count) == EGL_TRUE && count > 0) {
            out.push_back(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT,
                                                   devices[preferred % count], nullptr));
        }
    }
    if (hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
        out.push_back(
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
    }
    if (hasExtension(clientExtensions, "EGL_EXT_platform_device") &&
        hasExtension(clientExtensions, "EGL_EXT_device_enumeration")) {
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        if (eglQueryDevicesEXT(8, devices, &count) == EGL_TRUE) {
            for (EGLint n = 0; n < count; ++n) {
                out.push_back(
                    eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[n], nullptr));
            }
        }
    }
    out.push_back(eglGetDisplay(EGL_DEFAULT_DISPLAY));
    return out;
}

EGLContext createCoreContext(EGLDisplay display) {
    // 4.6 down to 4.3 (compute shaders, storage buffers): the newest the driver gives.
    for (const int minor : {6, 5, 4, 3}) {
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     minor,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
        // EGL_KHR_no_config_context: no surface, so no config is needed.
        const EGLContext context =
            eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
        if (context != EGL_NO_CONTEXT) {
            return context;
        }
    }
    return EGL_NO_CONTEXT;
}

} // namespace

OffscreenContext::OffscreenContext(std::unique_ptr<Egl> egl) : egl_(std::move(egl)) {}
OffscreenContext::~OffscreenContext() = default;

std::unique_ptr<OffscreenContext> OffscreenContext::create(int device) {
    std::string tried;
    for (const EGLDisplay display : candidateDisplays(device)) {
        if (display == EGL_NO_DISPLAY) {
            continue;
        }
        auto egl = std::make_unique<Egl>();
        EGLint major = 0, minor = 0;
        if (eglInitialize(display, &major, &minor) != EGL_TRUE) {
            tried += " (a display did not initialise)";
            continue;
        }
        useDisplay(display);
        egl->display = display;
        const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
        if (!hasExtension(extensions, "EGL_KHR_surfaceless_context") ||
            !hasExtension(extensions, "EGL_KHR_no_config_context")) {
            tried += " (a display without surfaceless contexts)";
            continue;
        }
        if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
            tried += " (a display without desktop OpenGL)";
            continue;
        }
        egl->context = createCoreContext(display);
        if (egl->context == EGL_NO_CONTEXT) {
            tried += " (a display without an OpenGL 4.3 core context)";
            continue;
        }
        if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl->context) != EGL_TRUE) {
            tried += " (a context that could not be made current)";
            continue;
        }
        if (epoxy_gl_version() < 43) {
            tried += " (OpenGL " + std::to_string(epoxy_gl_version()) + ", 43 needed)";
            continue;
        }
        return std::unique_ptr<OffscreenContext>(new OffscreenContext(std::move(egl)));
    }
    throw GlError("no OpenGL 4.3 core context through EGL" +
                  (tried.empty() ? std::string(" (no EGL display)") : ":" + tried));
}

void OffscreenContext::makeCurrent() {
    if (eglMakeCurrent(egl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl_->context) != EGL_TRUE) {
        throw GlError("eglMakeCurrent failed");
    }
}

std::string OffscreenContext::description() const {
    const auto text = [](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(glGetString(name));
        return std::string(s != nullptr ? s : "?");
    };
    return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

} // namespace lucent
