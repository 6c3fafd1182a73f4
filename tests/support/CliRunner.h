#pragma once
// Runs build/bin/lucent-cli as a user would, for the command-line tests.

#include <QProcess>
#include <QRegularExpression>
#include <QString>
#include <QStringList>

#include <cmath>

namespace lucent::test {

struct CliRun {
    int exitCode = -1; // -1 when the process crashed or timed out
    QString out;
    QString err;
};

// Runs `program` with `args`, waiting at most timeoutMs.
inline CliRun runProgram(const QString& program, const QStringList& args, int timeoutMs) {
    QProcess p;
    p.start(program, args);
    if (!p.waitForFinished(timeoutMs)) {
        p.kill();
        p.waitForFinished();
    }
    return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1,
            QString::fromUtf8(p.readAllStandardOutput()),
            QString::fromUtf8(p.readAllStandardError())};
}

inline CliRun runCli(const QStringList& args, int timeoutMs = 120000) {
    return runProgram(QString(LUCENT_BIN_DIR) + "/lucent-cli", args, timeoutMs);
}

// The number of `key=` in a --stats line; NaN when it is not there.
inline double statOf(const QString& out, const QString& key) {
    const auto m = QRegularExpression("(?:^| )" + key + "=(-?[0-9.]+(?:e[+-]?[0-9]+)?)").match(out);
    return m.hasMatch() ? m.captured(1).toDouble() : std::nan("");
}

} // namespace lucent::test
