#pragma once

#include <optional>
#include <span>

#include <QKeySequence>
#include <QString>

#include "core/measure/Measurement.h"

class QKeyEvent;

namespace lucent {

// What a left-drag on an MPR view does.
enum class SliceTool {
    Crosshair,
    Distance,
    Angle,
    CobbAngle,
    Arrow,
    Bidirectional,
    Ellipse,
    CurvedPath
};

// One row of the one table of tools: the tool bar, its tooltips, the view's context
// menu, its keys and Help > Keyboard shortcuts are all made from it.
struct SliceToolInfo {
    SliceTool tool;
    const char* name;                    // "Distance"
    const char* key;                     // as QKeySequence reads it: "D"
    const char* help;                    // how it is drawn
    std::optional<MeasurementKind> kind; // what it measures; none for the crosshair and path
};

std::span<const SliceToolInfo> sliceTools();
const SliceToolInfo& sliceToolInfo(SliceTool tool);
// The tool whose key `event` is (no modifiers but Shift); none if it is no tool's.
std::optional<SliceTool> sliceToolForKey(const QKeyEvent& event);
// "Distance (D)": the tooltip and status text of a tool's action.
QString sliceToolToolTip(const SliceToolInfo& info);

// The MPR view's other keys (not tools), as the view handles them: the shortcuts
// dialog lists them.
struct SliceKeyInfo {
    const char* keys;
    const char* what;
};
std::span<const SliceKeyInfo> sliceViewKeys();

} // namespace lucent
