#pragma once
// Widget tests run on Qt's offscreen platform unless QT_QPA_PLATFORM names
// one, so that a run from a desktop session paints what CI paints. A DISPLAY
// left set would let the offscreen plugin reach the X server for OpenGL (GLX),
// a different path from CI's: it is cleared, unless LUCENT_TEST_KEEP_DISPLAY
// asks for exactly that path (the workstation must fall back to the CPU there).

#include <QtGlobal>

namespace lucent::test {

inline void useOffscreenPlatform() {
    if (!qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) {
        return;
    }
    qputenv("QT_QPA_PLATFORM", "offscreen");
    if (qEnvironmentVariableIsEmpty("LUCENT_TEST_KEEP_DISPLAY")) {
        qunsetenv("DISPLAY");
        qunsetenv("WAYLAND_DISPLAY");
    }
}

} // namespace lucent::test
