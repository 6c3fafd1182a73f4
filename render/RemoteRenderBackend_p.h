#pragma once
// What the files of RemoteRenderBackend share: the connection
// (RemoteRenderBackend.cpp) and the view with its frames (RemoteRenderView.cpp).
// Private to render/.

#include <string>

#include <QString>

namespace lucent {

inline QString text(const std::string& s) {
    return QString::fromStdString(s);
}

} // namespace lucent
