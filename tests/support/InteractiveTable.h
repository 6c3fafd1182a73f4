#pragma once
// The table lucent-cli bench interactive prints ("| what | Lucent | anchor | ratio | goal |
// met |"), read back for its tests: the rows, and whether a cell holds a figure.

#include <QList>
#include <QRegularExpression>
#include <QString>
#include <QStringList>

namespace lucent::test {

struct InteractiveTableRow {
    QString what, lucent, anchor, ratio, goal, met;
};

// The rows under the header and its separator; a cell's "\|" is a '|' of its text.
inline QList<InteractiveTableRow> interactiveTableRows(const QString& out) {
    QList<InteractiveTableRow> rows;
    bool inTable = false;
    for (const QString& line : out.split('\n')) {
        if (line.startsWith("| what | Lucent |")) {
            inTable = true;
            continue;
        }
        if (!inTable || line.startsWith("|---") || !line.startsWith("| ")) {
            continue;
        }
        QStringList cells =
            line.mid(2, line.size() - 4).split(QRegularExpression(R"( (?<!\\)\| )"));
        for (QString& c : cells) {
            c.replace("\\|", "|");
        }
        if (cells.size() == 6) {
            rows.push_back({cells[0], cells[1], cells[2], cells[3], cells[4], cells[5]});
        } else {
            rows.push_back({line, "", "", "", "", ""}); // not six cells: the test names the line
        }
    }
    return rows;
}

// A cell that starts with a figure ("12.3 ms", "193 %", "41.2 fps").
inline bool holdsFigure(const QString& cell) {
    return QRegularExpression(R"(^-?[0-9]+(\.[0-9]+)? (ms|fps|%|dB))").match(cell).hasMatch();
}

} // namespace lucent::test
