#include "ui/pacs/PacsQueryPanel.h"

#include "ui/theme/Theme.h"
#include <QComboBox>
#include <QDateEdit>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QRegularExpression>
#include <QTreeWidget>
#include <QVBoxLayout>

namespace lucent {
namespace {

QString dicomDate(const std::string& d) {
    const QDate date = QDate::fromString(QString::fromStdString(d), QStringLiteral("yyyyMMdd"));
    return date.isValid() ? date.toString(Qt::ISODate) : QString::fromStdString(d);
}

} // namespace

PacsQueryPanel::PacsQueryPanel(PacsService* service, QWidget* parent)
    : QWidget(parent), service_(service), node_(new QComboBox(this)),
      patientName_(new QLineEdit(this)), patientId_(new QLineEdit(this)),
      accession_(new QLineEdit(this)), modalities_(new QLineEdit(this)),
      preset_(new QComboBox(this)), from_(new QDateEdit(this)), to_(new QDateEdit(this)),
      search_(new QPushButton(tr("&Search"), this)),
      retrieve_(new QPushButton(tr("&Retrieve selected"), this)), results_(new QTreeWidget(this)),
      status_(new QLabel(this)) {
    node_->setObjectName(QStringLiteral("node"));
    patientName_->setObjectName(QStringLiteral("patientName"));
    patientName_->setPlaceholderText(tr("e.g. Smith* (wildcards * and ?)"));
    patientId_->setObjectName(QStringLiteral("patientId"));
    accession_->setObjectName(QStringLiteral("accession"));
    modalities_->setObjectName(QStringLiteral("modalities"));
    modalities_->setPlaceholderText(tr("e.g. CT,MR (empty: all)"));
    preset_->setObjectName(QStringLiteral("datePreset"));
    preset_->addItems(
        {tr("Any date"), tr("Today"), tr("Last 7 days"), tr("Last month"), tr("Custom range")});
    for (QDateEdit* edit : {from_, to_}) {
        edit->setCalendarPopup(true);
        edit->setDisplayFormat(QStringLiteral("yyyy-MM-dd"));
        edit->setDate(QDate::currentDate());
        edit->setEnabled(false);
    }
    from_->setObjectName(QStringLiteral("dateFrom"));
    to_->setObjectName(QStringLiteral("dateTo"));
    search_->setObjectName(QStringLiteral("search"));
    search_->setDefault(true);
    retrieve_->setObjectName(QStringLiteral("retrieve"));
    results_->setObjectName(QStringLiteral("results"));
    results_->setHeaderLabels({tr("Patient / series"), tr("ID"), tr("Date"), tr("Modality"),
                               tr("Description"), tr("Images")});
    results_->setSelectionMode(QAbstractItemView::ExtendedSelection);
    results_->header()->setSectionResizeMode(Name, QHeaderView::ResizeToContents);
    status_->setObjectName(QStringLiteral("queryStatus"));
    status_->setWordWrap(true);

    auto* form = new QFormLayout;
    form->addRow(tr("PACS"), node_);
    form->addRow(tr("Patient name"), patientName_);
    form->addRow(tr("Patient ID"), patientId_);
    form->addRow(tr("Accession"), accession_);
    form->addRow(tr("Modalities"), modalities_);
    auto* dates = new QHBoxLayout;
    dates->addWidget(preset_);
    dates->addWidget(from_);
    dates->addWidget(new QLabel(QStringLiteral("-"), this));
    dates->addWidget(to_);
    form->addRow(tr("Study date"), dates);
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(search_);
    buttons->addStretch();
    buttons->addWidget(retrieve_);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addLayout(buttons);
    layout->addWidget(status_);
    layout->addWidget(results_, 1);

    connect(preset_, &QComboBox::activated, this,
            [this](int index) { applyPreset(static_cast<DatePreset>(index)); });
    for (QDateEdit* edit : {from_, to_}) {
        connect(edit, &QDateEdit::userDateChanged, this, [this] {
            if (preset_->currentIndex() != static_cast<int>(DatePreset::AnyDate)) {
                preset_->setCurrentIndex(static_cast<int>(DatePreset::Custom));
            }
        });
    }
    connect(search_, &QPushButton::clicked, this, &PacsQueryPanel::search);
    for (QLineEdit* edit : {patientName_, patientId_, accession_, modalities_}) {
        connect(edit, &QLineEdit::returnPressed, this, &PacsQueryPanel::search);
    }
    connect(retrieve_, &QPushButton::clicked, this, &PacsQueryPanel::retrieveSelected);
    connect(results_, &QTreeWidget::itemDoubleClicked, this, [this](QTreeWidgetItem* item) {
        results_->clearSelection();
        item->setSelected(true);
        retrieveSelected();
    });
    connect(service_, &PacsService::queryFinished, this, &PacsQueryPanel::showResults);
    connect(service_, &PacsService::queryFailed, this, &PacsQueryPanel::showError);
}

void PacsQueryPanel::setNodes(const QList<PacsNodeConfig>& nodes) {
    const QString current = node_->currentText();
    nodes_ = nodes;
    node_->clear();
    for (const PacsNodeConfig& n : nodes_) {
        node_->addItem(n.name);
    }
    if (const int i = node_->findText(current); i >= 0) {
        node_->setCurrentIndex(i);
    }
}

const PacsNodeConfig* PacsQueryPanel::currentNode() const {
    const int i = node_->currentIndex();
    return i >= 0 && i < nodes_.size() ? &nodes_[i] : nullptr;
}

void PacsQueryPanel::applyPreset(DatePreset preset) {
    preset_->setCurrentIndex(static_cast<int>(preset));
    const QDate today = QDate::currentDate();
    switch (preset) {
    case DatePreset::Today:
        from_->setDate(today);
        break;
    case DatePreset::Last7Days:
        from_->setDate(today.addDays(-6));
        break;
    case DatePreset::LastMonth:
        from_->setDate(today.addMonths(-1));
        break;
    case DatePreset::AnyDate:
    case DatePreset::Custom:
        break;
    }
    if (preset != DatePreset::AnyDate && preset != DatePreset::Custom) {
        to_->setDate(today);
    }
    from_->setEnabled(preset != DatePreset::AnyDate);
    to_->setEnabled(preset != DatePreset::AnyDate);
}

QueryFilter PacsQueryPanel::filter(QString* error) const {
    QueryFilter f;
    f.patientName = patientName_->text().trimmed().toStdString();
    f.patientId = patientId_->text().trimmed().toStdString();
    f.accessionNumber = accession_->text().trimmed().toStdString();
    for (const QString& m : modalities_->text().split(
             QRegularExpression(QStringLiteral("[,;\\s]+")), Qt::SkipEmptyParts)) {
        f.modalities.push_back(m.toUpper().toStdString());
    }
    QString problem;
    if (preset_->currentIndex() != static_cast<int>(DatePreset::AnyDate)) {
        if (from_->date() > to_->date()) {
            problem =
                tr("Study date: the start %1 is after the end %2")
                    .arg(from_->date().toString(Qt::ISODate), to_->date().toString(Qt::ISODate));
        }
        f.dateRange = (from_->date().toString(QStringLiteral("yyyyMMdd")) + "-" +
                       to_->date().toString(QStringLiteral("yyyyMMdd")))
                          .toStdString();
    }
    for (const std::string& m : f.modalities) {
        if (m.size() > 16 ||
            m.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") != std::string::npos) {
            problem = tr("Modalities: '%1' is not a modality (letters such as CT or MR)")
                          .arg(QString::fromStdString(m));
        }
    }
    if (problem.isEmpty()) {
        try {
            f.validate();
        } catch (const PacsError& e) {
            problem = QString::fromStdString(e.what());
        }
    }
    if (error != nullptr) {
        *error = problem;
    }
    return f;
}

void PacsQueryPanel::search() {
    const PacsNodeConfig* node = currentNode();
    if (node == nullptr) {
        showError(tr("PACS: no node configured (PACS > PACS nodes...)"));
        return;
    }
    QString problem;
    const QueryFilter f = filter(&problem);
    if (!problem.isEmpty()) {
        showError(problem);
        return;
    }
    searching_ = true;
    search_->setEnabled(false);
    status_->setStyleSheet({});
    status_->setText(tr("Searching %1...").arg(node->name));
    service_->query(*node, f);
}

void PacsQueryPanel::showResults(const std::vector<PacsStudyResult>& results) {
    searching_ = false;
    search_->setEnabled(true);
    results_->clear();
    int series = 0;
    for (const PacsStudyResult& r : results) {
        const QueryMatch& s = r.study;
        auto* study = new QTreeWidgetItem(results_);
        study->setText(Name, QString::fromStdString(s.patientName));
        study->setText(Id, QString::fromStdString(s.patientId));
        study->setText(Date, dicomDate(s.studyDate));
        study->setText(Modality, QString::fromStdString(s.modalitiesInStudy));
        study->setText(Description,
                       QString::fromStdString(s.studyDescription) +
                           (s.accessionNumber.empty()
                                ? QString()
                                : " [" + QString::fromStdString(s.accessionNumber) + "]"));
        study->setText(Instances, s.instances > 0 ? QString::number(s.instances) : QString());
        study->setData(Name, kUidRole, QString::fromStdString(s.studyUid));
        for (const QueryMatch& m : r.series) {
            auto* item = new QTreeWidgetItem(study);
            item->setText(Name, tr("Series %1").arg(m.seriesNumber));
            item->setText(Modality, QString::fromStdString(m.modality));
            item->setText(Description, QString::fromStdString(m.seriesDescription));
            item->setText(Instances, QString::number(m.instances));
            item->setData(Name, kUidRole, QString::fromStdString(m.seriesUid));
            item->setData(Name, kStudyUidRole, QString::fromStdString(s.studyUid));
            ++series;
        }
        study->setExpanded(true);
    }
    status_->setStyleSheet({});
    status_->setText(tr("%n study(ies)", nullptr, static_cast<int>(results.size())) + ", " +
                     tr("%n series", nullptr, series));
}

void PacsQueryPanel::showError(const QString& message) {
    searching_ = false;
    search_->setEnabled(true);
    status_->setStyleSheet(statusStyleSheet(StatusTone::Error));
    status_->setText(message);
}

void PacsQueryPanel::retrieveSelected() {
    const PacsNodeConfig* node = currentNode();
    if (node == nullptr) {
        showError(tr("PACS: no node configured (PACS > PACS nodes...)"));
        return;
    }
    QList<SeriesRequest> requests;
    QStringList seen;
    auto add = [&](QTreeWidgetItem* series) {
        const QString uid = series->data(Name, kUidRole).toString();
        if (seen.contains(uid)) {
            return;
        }
        seen << uid;
        QTreeWidgetItem* study = series->parent();
        requests << SeriesRequest{series->data(Name, kStudyUidRole).toString(), uid,
                                  study->text(Name) + " - " + series->text(Name) + " " +
                                      series->text(Description)};
    };
    for (QTreeWidgetItem* item : results_->selectedItems()) {
        if (item->parent() != nullptr) {
            add(item);
        } else {
            for (int i = 0; i < item->childCount(); ++i) {
                add(item->child(i));
            }
        }
    }
    if (requests.isEmpty()) {
        showError(tr("Select a study or series to retrieve"));
        return;
    }
    status_->setStyleSheet({});
    status_->setText(tr("Retrieving %n series from %1", nullptr, static_cast<int>(requests.size()))
                         .arg(node->name));
    service_->retrieve(*node, requests);
}

} // namespace lucent
