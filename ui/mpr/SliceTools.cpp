#include "ui/mpr/SliceTools.h"

#include <algorithm>
#include <array>

#include <QKeyEvent>

namespace lucent {

namespace {

constexpr std::array<SliceToolInfo, 8> kTools{{
    {SliceTool::Crosshair, "Crosshair", "Esc", "Click or drag to move the crosshair", std::nullopt},
    {SliceTool::Distance, "Distance", "D", "Drag, or click both ends", MeasurementKind::Distance},
    {SliceTool::Angle, "Angle", "A",
     "Drag the first arm to the vertex, then click the second arm's end (or click three points)",
     MeasurementKind::Angle},
    {SliceTool::CobbAngle, "Cobb angle", "K", "Drag (or click) two lines",
     MeasurementKind::CobbAngle},
    {SliceTool::Arrow, "Arrow", "T", "Drag from the finding to where the text goes, then type",
     MeasurementKind::Arrow},
    {SliceTool::Bidirectional, "Bidirectional", "B",
     "Drag the long axis; drag the short axis' ends to adjust it (RECIST)",
     MeasurementKind::Bidirectional},
    {SliceTool::Ellipse, "Ellipse ROI", "E", "Drag the box around the ellipse (mean, SD, area)",
     MeasurementKind::Ellipse},
    {SliceTool::CurvedPath, "Curved path", "P",
     "Click points; a double-click or Enter opens the curved MPR", std::nullopt},
}};

constexpr std::array<SliceKeyInfo, 14> kViewKeys{{
    {"1 ... 8", "Window presets: brain, subdural, stroke, lung, mediastinum, abdomen, liver, bone"},
    {"S", "Slab mode: thin, MIP, MinIP, average"},
    {"[  ]", "Thinner / thicker slab"},
    {"C", "Cine on or off"},
    {"R", "Reset zoom and pan"},
    {"O", "Reset oblique planes"},
    {"Del", "Delete the selected measurement"},
    {"Enter", "End the curved path"},
    {"Menu", "The view's context menu"},
    {"Wheel", "Next or previous slice"},
    {"Ctrl+Wheel", "Zoom about the mouse"},
    {"Right drag", "Window (left-right) and level (up-down); a right-click opens the menu"},
    {"Middle drag", "Pan"},
    {"Shift+Left drag", "Turn the other two planes (oblique MPR)"},
}};

} // namespace

std::span<const SliceToolInfo> sliceTools() {
    return kTools;
}

const SliceToolInfo& sliceToolInfo(SliceTool tool) {
    return *std::find_if(kTools.begin(), kTools.end(),
                         [tool](const SliceToolInfo& info) { return info.tool == tool; });
}

std::optional<SliceTool> sliceToolForKey(const QKeyEvent& event) {
    if (event.modifiers() & ~(Qt::ShiftModifier | Qt::KeypadModifier)) {
        return std::nullopt;
    }
    const QKeySequence pressed(event.key());
    for (const SliceToolInfo& info : kTools) {
        if (QKeySequence(QString::fromLatin1(info.key)) == pressed) {
            return info.tool;
        }
    }
    return std::nullopt;
}

QString sliceToolToolTip(const SliceToolInfo& info) {
    return QStringLiteral("%1 (%2)").arg(QString::fromLatin1(info.name),
                                         QString::fromLatin1(info.key));
}

std::span<const SliceKeyInfo> sliceViewKeys() {
    return kViewKeys;
}

} // namespace lucent
