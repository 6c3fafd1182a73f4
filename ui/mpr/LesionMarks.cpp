#include "ui/mpr/LesionMarks.h"

#include <QAction>
#include <QMenu>
#include <QPointer>

#include "core/report/MeasurementReport.h"
#include "ui/mpr/SeriesMeasurements.h"

namespace lucent {

namespace {

// The measurement `id` with `mark` applied, as one edit. A new lesion gets a tracking UID
// and, when unnamed, "Lesion N" (N: the lesions of the series, this one included).
void mark(SeriesMeasurements& measurements, std::uint64_t id,
          const std::function<void(Measurement&)>& apply) {
    const Measurement* found = measurements.find(id);
    if (found == nullptr || found->readOnly) {
        return;
    }
    Measurement m = *found;
    apply(m);
    if (m.lesion.role != LesionRole::None && m.lesion.trackingUid.empty()) {
        m.lesion.trackingUid = newDicomUid();
    }
    if (m.lesion.role != LesionRole::None && m.label.empty()) {
        int lesions = 1;
        for (const Measurement& other : measurements.measurements()) {
            lesions += other.id != id && other.lesion.role != LesionRole::None ? 1 : 0;
        }
        m.label = "Lesion " + std::to_string(lesions);
    }
    if (m.lesion != found->lesion || m.label != found->label) {
        measurements.change(std::move(m));
    }
}

} // namespace

std::string lesionMarkText(const LesionTracking& lesion) {
    if (lesion.role == LesionRole::None) {
        return {};
    }
    return std::string(lesionRoleName(lesion.role)) + (lesion.lymphNode ? ", node" : "");
}

void addLesionActions(QMenu& menu, SeriesMeasurements& measurements, std::uint64_t id,
                      const std::vector<LesionChoice>& earlier) {
    const Measurement* m = measurements.find(id);
    const bool markable = m != nullptr && !m->readOnly && m->kind != MeasurementKind::Angle &&
                          m->kind != MeasurementKind::CobbAngle;
    const LesionTracking current = m != nullptr ? m->lesion : LesionTracking{};
    QPointer<SeriesMeasurements> target(&measurements);
    const auto addMark = [&](const QString& text, const char* name, bool checked,
                             std::function<void(Measurement&)> apply) {
        QAction* action = menu.addAction(text);
        action->setObjectName(QString::fromLatin1(name));
        action->setCheckable(true);
        action->setChecked(checked);
        action->setEnabled(markable);
        QObject::connect(action, &QAction::triggered, action, [target, id, apply] {
            if (target != nullptr) {
                mark(*target, id, apply);
            }
        });
    };
    addMark(QObject::tr("Target lesion"), "lesionTarget", current.role == LesionRole::Target,
            [](Measurement& x) { x.lesion.role = LesionRole::Target; });
    addMark(QObject::tr("Non-target lesion"), "lesionNonTarget",
            current.role == LesionRole::NonTarget,
            [](Measurement& x) { x.lesion.role = LesionRole::NonTarget; });
    addMark(QObject::tr("Lymph node (short axis)"), "lesionLymphNode", current.lymphNode,
            [](Measurement& x) {
                x.lesion.lymphNode = !x.lesion.lymphNode;
                if (x.lesion.role == LesionRole::None) {
                    x.lesion.role = LesionRole::Target; // a node marked to be measured
                }
            });
    addMark(QObject::tr("Not a lesion"), "lesionNone", current.role == LesionRole::None,
            [](Measurement& x) {
                x.lesion.role = LesionRole::None;
                x.lesion.lymphNode = false;
            });

    QMenu* same = menu.addMenu(QObject::tr("Same lesion as"));
    same->setObjectName(QStringLiteral("lesionSameAs"));
    for (const LesionChoice& choice : earlier) {
        bool taken = false;
        for (const Measurement& other : measurements.measurements()) {
            taken = taken || (other.id != id && other.lesion.trackingUid == choice.trackingUid);
        }
        if (taken) {
            continue;
        }
        const QString date = QString::fromStdString(choice.studyDate);
        QAction* action = same->addAction(
            QObject::tr("%1 (%2, %3)")
                .arg(QString::fromStdString(choice.name),
                     QString::fromLatin1(lesionRoleName(choice.role)).toLower(),
                     date.size() == 8 ? date.left(4) + '-' + date.mid(4, 2) + '-' + date.right(2)
                                      : date));
        action->setData(QString::fromStdString(choice.trackingUid));
        action->setCheckable(true);
        action->setChecked(current.trackingUid == choice.trackingUid);
        QObject::connect(action, &QAction::triggered, action, [target, id, choice] {
            if (target != nullptr) {
                mark(*target, id, [&choice](Measurement& x) {
                    x.lesion = {choice.role, choice.lymphNode, choice.trackingUid};
                    x.label = choice.name;
                });
            }
        });
    }
    same->setEnabled(markable && !same->isEmpty());
}

} // namespace lucent
