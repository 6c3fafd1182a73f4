#include "ui/priors/PriorTimeline.h"

#include <utility>

#include <QHeaderView>
#include <QLabel>
#include <QPalette>
#include <QPushButton>
#include <QTreeWidget>
#include <QVBoxLayout>

#include "core/pacs/PriorsForStudy.h"
#include "core/volume/SeriesInfo.h"

namespace lucent {

namespace {

enum Column { kDate, kRole, kStudy, kWhere, kState };

QString roleOf(const PatientStudy& s) {
    if (s.order == 0) {
        return PriorTimeline::tr("current");
    }
    return s.order > 0 ? PriorTimeline::tr("prior %1").arg(s.order) : QString();
}

QString whereOf(const PatientStudy& s, const QList<PacsNodeConfig>& nodes) {
    QStringList where;
    if (!s.storeFolder.empty()) {
        where << PriorTimeline::tr("store");
    }
    for (const int n : s.nodes) {
        if (n >= 0 && n < nodes.size()) {
            where << nodes[n].name;
        }
    }
    return where.join(QStringLiteral(", "));
}

QString kindsOf(const PatientStudy& s) {
    QStringList kinds;
    for (const std::string& m : s.modalities()) {
        kinds << QString::fromStdString(m);
    }
    QString text = kinds.join('/');
    for (const std::string& b : s.bodyParts()) {
        text += ' ' + QString::fromStdString(b);
    }
    if (!s.description.empty()) {
        text += QStringLiteral(" — ") + QString::fromStdString(s.description);
    }
    return text;
}

} // namespace

QString readingSeries(const PatientStudy& study, const CurrentStudy& current) {
    const PatientSeries* best = nullptr;
    for (const PatientSeries& s : study.series) {
        const auto rank = [&](const PatientSeries& p) {
            return std::pair(p.modality == current.modality, p.instances);
        };
        if (best == nullptr || rank(s) > rank(*best)) {
            best = &s;
        }
    }
    return best == nullptr ? QString() : QString::fromStdString(best->seriesUid);
}

PriorTimeline::PriorTimeline(PriorsForStudy& priors, QWidget* parent)
    : QWidget(parent), priors_(priors), heading_(new QLabel(this)), list_(new QTreeWidget(this)),
      cancel_(new QPushButton(tr("Cancel fetches"), this)) {
    list_->setObjectName(QStringLiteral("priorTimeline"));
    list_->setHeaderLabels({tr("Date"), tr(""), tr("Study"), tr("Where"), tr("State")});
    list_->setRootIsDecorated(false);
    list_->header()->setSectionResizeMode(QHeaderView::ResizeToContents);
    heading_->setWordWrap(true);
    heading_->setText(tr("Open a study to see the patient's priors."));
    cancel_->setEnabled(false);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(heading_);
    layout->addWidget(list_, 1);
    layout->addWidget(cancel_, 0, Qt::AlignRight);

    connect(list_, &QTreeWidget::itemActivated, this, [this](QTreeWidgetItem* item) {
        activate(item->data(kDate, Qt::UserRole).toString());
    });
    connect(cancel_, &QPushButton::clicked, &priors_, &PriorsForStudy::cancel);
    connect(&priors_, &PriorsForStudy::lookupStarted, this, [this] {
        list_->clear();
        heading_->setText(
            tr("Looking for patient %1's studies in the store and on %2 PACS node(s)…")
                .arg(QString::fromStdString(priors_.current().patientId))
                .arg(priors_.nodes().size()));
    });
    connect(&priors_, &PriorsForStudy::studiesFound, this, &PriorTimeline::rebuild);
    connect(&priors_, &PriorsForStudy::fetchStarted, this, [this](const QString& uid) {
        setState(uid, tr("fetching…"));
        cancel_->setEnabled(true);
    });
    connect(&priors_, &PriorsForStudy::fetchProgress, this,
            [this](const QString& uid, int done, int total) {
                setState(uid, tr("fetching %1 of %2").arg(done).arg(total));
            });
    connect(&priors_, &PriorsForStudy::fetchFailed, this,
            [this](const QString& uid, const QString& why) {
                rebuild();
                setState(uid, tr("failed: %1").arg(why));
            });
    connect(&priors_, &PriorsForStudy::studyFetched, this,
            [this](const QString& uid, const QString&, const QStringList&) {
                rebuild();
                if (uid == openWhenFetched_) {
                    openWhenFetched_.clear();
                    activate(uid);
                }
            });
}

void PriorTimeline::rebuild() {
    list_->clear();
    const auto& studies = priors_.studies();
    QString text = tr("Patient %1: %2 studies")
                       .arg(QString::fromStdString(priors_.current().patientId))
                       .arg(studies.size());
    if (!priors_.nodeErrors().isEmpty()) {
        text += tr("; not asked: %1").arg(priors_.nodeErrors().join(QStringLiteral("; ")));
    }
    heading_->setText(text);
    bool fetching = false;
    for (const PatientStudy& s : studies) {
        const QString uid = QString::fromStdString(s.studyUid);
        auto* item = new QTreeWidgetItem(list_);
        item->setText(kDate, QString::fromStdString(formatStudyDate(s.studyDate)));
        item->setData(kDate, Qt::UserRole, uid);
        item->setText(kRole, roleOf(s));
        item->setText(kStudy, kindsOf(s));
        item->setText(kWhere, whereOf(s, priors_.nodes()));
        item->setText(kState, priors_.isFetching(uid) ? tr("fetching…")
                              : s.completeInStore()   ? tr("in the store")
                                                      : tr("on PACS"));
        item->setToolTip(kStudy, QString::fromStdString(describeStudy(s)));
        fetching = fetching || priors_.isFetching(uid);
        if (!s.comparable && s.order != 0) {
            for (int c = 0; c <= kState; ++c) {
                item->setForeground(c, palette().brush(QPalette::Disabled, QPalette::Text));
            }
        }
    }
    cancel_->setEnabled(fetching);
}

QTreeWidgetItem* PriorTimeline::itemOf(const QString& studyUid) const {
    for (int n = 0; n < list_->topLevelItemCount(); ++n) {
        if (list_->topLevelItem(n)->data(kDate, Qt::UserRole).toString() == studyUid) {
            return list_->topLevelItem(n);
        }
    }
    return nullptr;
}

void PriorTimeline::setState(const QString& studyUid, const QString& state) {
    if (QTreeWidgetItem* item = itemOf(studyUid)) {
        item->setText(kState, state);
        item->setToolTip(kState, state);
    }
}

void PriorTimeline::activate(const QString& studyUid) {
    const PatientStudy* s = priors_.study(studyUid);
    if (s == nullptr) {
        return;
    }
    if (s->completeInStore()) {
        emit openStudy(QString::fromStdString(s->storeFolder),
                       readingSeries(*s, priors_.current()));
        return;
    }
    openWhenFetched_ = studyUid;
    if (!priors_.isFetching(studyUid) && !priors_.fetch(studyUid)) {
        openWhenFetched_.clear();
        setState(studyUid, tr("on no reachable PACS node"));
    }
}

} // namespace lucent
