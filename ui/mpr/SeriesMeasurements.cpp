#include "ui/mpr/SeriesMeasurements.h"

#include <algorithm>

namespace lucent {

SeriesMeasurements::SeriesMeasurements(std::shared_ptr<const Volume> volume, QObject* parent)
    : QObject(parent) {
    setVolume(std::move(volume));
}

void SeriesMeasurements::setVolume(std::shared_ptr<const Volume> volume) {
    if (volume) {
        seriesUid_ = volume->seriesUid;
    }
    volume_ = volume;
}

void SeriesMeasurements::measure(Measurement& m) const {
    const std::shared_ptr<const Volume> volume = volume_.lock();
    if (m.kind != MeasurementKind::Ellipse || !volume || volume->empty() || !m.complete()) {
        return;
    }
    // At least two samples per voxel across, whatever the zoom it was drawn at.
    const glm::dvec3 s = volume->geometry().spacing;
    const double spacing = std::min(m.plane.pixelSize, 0.5 * std::min({s.x, s.y, s.z}));
    m.statistics = ellipseStatistics(*volume, m.plane, measurementEllipse(m), spacing);
    m.unit = measurementUnit(*volume);
    m.suv = measurementSuv(*volume, m);
}

void SeriesMeasurements::edited() {
    if (selected_ != 0 && document_.find(selected_) == nullptr) {
        select(0);
    }
    emit changed();
}

std::uint64_t SeriesMeasurements::add(Measurement m) {
    measure(m);
    const std::uint64_t id = document_.add(std::move(m));
    selected_ = id;
    edited();
    emit selectionChanged(id);
    return id;
}

bool SeriesMeasurements::change(Measurement m) {
    measure(m);
    if (!document_.change(m)) {
        return false;
    }
    edited();
    return true;
}

bool SeriesMeasurements::rename(std::uint64_t id, const std::string& label) {
    if (!document_.rename(id, label)) {
        return false;
    }
    edited();
    return true;
}

bool SeriesMeasurements::remove(std::uint64_t id) {
    if (!document_.remove(id)) {
        return false;
    }
    edited();
    return true;
}

void SeriesMeasurements::clear() {
    const std::uint64_t before = document_.revision();
    document_.clear();
    if (document_.revision() != before) {
        edited();
    }
}

bool SeriesMeasurements::undo() {
    if (!document_.undo()) {
        return false;
    }
    edited();
    return true;
}

bool SeriesMeasurements::redo() {
    if (!document_.redo()) {
        return false;
    }
    edited();
    return true;
}

void SeriesMeasurements::load(std::vector<Measurement> measurements) {
    document_.load(std::move(measurements));
    edited();
}

void SeriesMeasurements::select(std::uint64_t id) {
    if (id == selected_) {
        return;
    }
    selected_ = id;
    emit selectionChanged(id);
}

void SeriesMeasurements::setNotShown(std::vector<std::string> items) {
    notShown_ = std::move(items);
    emit changed();
}

} // namespace lucent
