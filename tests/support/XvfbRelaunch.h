#pragma once
// For GL widget tests: QOpenGLWidget needs a display. Without one (no DISPLAY,
// no QT_QPA_PLATFORM chosen), the test runs itself again under xvfb-run.

#include <QtGlobal>

#include <cstdio>
#include <vector>

#include <unistd.h>

namespace lucent::test {

// Returns only when the test should go on here (-1), or when xvfb-run could
// not be started (the exit status to return, with a message).
inline int relaunchUnderXvfbWhenHeadless(int argc, char** argv) {
    if (!qEnvironmentVariableIsEmpty("DISPLAY") ||
        !qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM") ||
        !qEnvironmentVariableIsEmpty("LUCENT_UNDER_XVFB")) {
        return -1;
    }
    qputenv("LUCENT_UNDER_XVFB", "1");
    std::vector<char*> args = {const_cast<char*>("xvfb-run"), const_cast<char*>("-a"),
                               const_cast<char*>("-s"),
                               const_cast<char*>("-screen 0 1280x1024x24")};
    for (int n = 0; n < argc; ++n) {
        args.push_back(argv[n]);
    }
    args.push_back(nullptr);
    execvp("xvfb-run", args.data());
    std::fprintf(stderr,
                 "%s: no DISPLAY and xvfb-run cannot be started "
                 "(packaging/install-deps.sh installs xvfb and xauth)\n",
                 argv[0]);
    return 1;
}

} // namespace lucent::test
