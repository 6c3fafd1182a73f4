#pragma once
// Runs build/bin/lucent-cli as a user would, for the command-line tests.

#include <QProcess>
#include <QString>
#include <QStringList>

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

} // namespace lucent::test
