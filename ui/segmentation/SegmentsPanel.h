#pragma once
// The Segments dock: the segments of the active viewport's series (name, colour, shown,
// locked, SNOMED CT kind), add, remove, undo and redo (Ctrl+Z, Ctrl+Y within the panel),
// the Segment Editor's effects (paint, erase, draw, threshold against the histogram,
// islands, margin, hollow, smoothing, logical operators), how segments are drawn, the
// statistics table with its CSV, and labelmap NIfTI export and import.
// Other tools join through addEffectButton (the "More" tab).

#include <cstdint>
#include <functional>
#include <vector>

#include <QPointer>
#include <QWidget>

#include "core/segmentation/SegmentStatisticsCsv.h"
#include "ui/segmentation/SegmentationSession.h"

class QButtonGroup;
class QCheckBox;
class QComboBox;
class QKeyEvent;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QTabWidget;
class QTableWidget;
class QTimer;
class QVBoxLayout;

namespace lucent {

class SegmentEditor;
class ThresholdHistogram;

class SegmentsPanel : public QWidget {
    Q_OBJECT

public:
    explicit SegmentsPanel(SegmentEditor* editor, QWidget* parent = nullptr);

    SegmentEditor* editor() const { return editor_; }
    // The session shown: the active viewport's series'; nullptr when it shows no volume.
    SegmentationSession* session() const { return session_; }

    // A button in the "More" tab that runs `action` on the active series' segments and its
    // active segment (a locked or missing segment is refused before): the hook for the 3D
    // scissors, grow from seeds, surfaces, masked rendering. An action that edits
    // session.segmentation() directly calls session.notifyChanged() after (the views and
    // the list follow); session.apply() does that itself.
    using SegmentAction = std::function<void(SegmentationSession& session, std::uint32_t segment)>;
    QPushButton* addEffectButton(const QString& text, const QString& toolTip, SegmentAction action);
    // A group of controls of its own on the "More" tab (the 3D tools, grow from seeds).
    void addEffectWidget(QWidget* widget);

    // What the controls do (for tests and shortcuts); false with lastMessage() saying why.
    bool addSegment();
    bool removeActiveSegment();
    bool undo();
    bool redo();
    void setThresholdRange(double lo, double hi);
    void setThresholdPreview(bool on);
    bool applyThreshold();
    bool keepLargestIsland();
    bool removeSmallIslands(double minMm3);
    bool margin(double mm); // > 0 grows, < 0 shrinks
    bool hollow(double thicknessMm);
    bool median(double kernelMm);
    bool closing(double radiusMm);
    enum class Logical { Add, Subtract, Intersect };
    bool combine(Logical operation, std::uint32_t other);
    bool invert();
    // The statistics of every segment, shown in the table.
    std::vector<NamedStatistics> computeStatistics();
    // Files: false with lastMessage() naming the file and what went wrong.
    bool exportStatisticsCsv(const QString& path);
    bool exportLabelmap(const QString& path);
    bool importLabelmap(const QString& path);

    QTableWidget* segmentTable() const { return segments_; }
    QTableWidget* statisticsTable() const { return statistics_; }
    ThresholdHistogram* thresholdHistogram() const { return histogram_; }
    const QString& lastMessage() const { return message_; }

signals:
    void message(const QString& text, int timeoutMs);

protected:
    bool event(QEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;

private:
    QWidget* makeListControls();
    QWidget* makeEffects();
    QWidget* makePaintTab();
    QWidget* makeThresholdTab();
    QWidget* makeIslandsTab();
    QWidget* makeMarginTab();
    QWidget* makeLogicalTab();
    QWidget* makeDataControls();
    void showSession(SegmentationSession* session);
    void fillTable();
    void selectActive(); // the active segment's row, without rebuilding the list
    void fillRow(int row, const Segment& segment);
    void cellEdited(int row, int column);
    void rowChosen();
    void updateThresholdPreview();
    void say(const QString& text);

    SegmentEditor* editor_;
    QPointer<SegmentationSession> session_;
    QLabel* series_;
    QTableWidget* segments_;
    QPushButton* undo_;
    QPushButton* redo_;
    QButtonGroup* tools_;
    QDoubleSpinBox* brushRadius_;
    QCheckBox* sphere_;
    ThresholdHistogram* histogram_;
    QDoubleSpinBox* lower_;
    QDoubleSpinBox* upper_;
    QCheckBox* preview_;
    QTimer* previewTimer_;
    QComboBox* other_;
    QVBoxLayout* more_;
    QTableWidget* statistics_;
    QString message_;
    const Volume* histogramOf_ = nullptr; // whose values the histogram shows
    bool updating_ = false;
};

} // namespace lucent
