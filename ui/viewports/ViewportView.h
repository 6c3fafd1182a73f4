#pragma once
// TEMPORARY until the hanging-protocol branch lands (its core/hanging/HangingProtocol.h
// is the one home of this enum).
namespace lucent {
enum class ViewportView { Axial, Coronal, Sagittal, Oblique, Volume3D, Stack };
}
