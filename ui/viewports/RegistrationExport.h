#pragma once
// "Save Registrations to the Study Store (DICOM)": the transforms the active viewport's
// series (fixed) has with the series of the other viewports, each written as a DICOM
// Spatial Registration object (core/exchange) into the study store, in the fixed series'
// study, so it can be sent to PACS like any series.

#include <vector>

#include <QString>

namespace lucent {

class Viewport;
class ViewportWorkspace;

struct SavedRegistration {
    QString fixedSeries; // Series Instance UIDs
    QString movingSeries;
    QString sopInstanceUid; // of the Spatial Registration object stored
};

// One object per pair with a kept transform (a registration or a nudge). Pairs that cannot
// be written (not DICOM, files gone) are named in `message` with the reason; so is a
// workspace without a study store or a viewport without a volume.
std::vector<SavedRegistration> saveRegistrations(ViewportWorkspace& workspace, Viewport* fixed,
                                                 QString* message = nullptr);

} // namespace lucent
