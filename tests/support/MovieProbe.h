#pragma once
// ffprobe and ffmpeg for the movie tests: what a movie file holds, and its
// frames decoded to PNG. Each fails the test with a message when the program
// is missing (packaging/install-deps.sh installs ffmpeg).

#include <QDir>
#include <QStandardPaths>
#include <QString>
#include <QStringList>

#include "tests/support/CliRunner.h"

namespace lucent::test {

struct ProbedMovie {
    QString codec;
    int width = 0, height = 0;
    int frames = -1; // decoded frames (ffprobe -count_frames)
    QString error;   // why the probe failed, or empty
};

inline QString ffmpegTool(const QString& name) {
    return QStandardPaths::findExecutable(name);
}

inline ProbedMovie probeMovie(const QString& file) {
    ProbedMovie m;
    const QString ffprobe = ffmpegTool("ffprobe");
    if (ffprobe.isEmpty()) {
        m.error = "ffprobe not found (apt-get install ffmpeg)";
        return m;
    }
    const CliRun r = runProgram(ffprobe,
                                {"-v", "error", "-count_frames", "-select_streams", "v:0",
                                 "-show_entries", "stream=codec_name,width,height,nb_read_frames",
                                 "-of", "default=noprint_wrappers=1", file},
                                60000);
    if (r.exitCode != 0) {
        m.error = "ffprobe " + file + ": " + r.err;
        return m;
    }
    for (const QString& line : r.out.split('\n', Qt::SkipEmptyParts)) {
        const QString key = line.section('=', 0, 0), value = line.section('=', 1).trimmed();
        if (key == "codec_name") {
            m.codec = value;
        } else if (key == "width") {
            m.width = value.toInt();
        } else if (key == "height") {
            m.height = value.toInt();
        } else if (key == "nb_read_frames") {
            m.frames = value.toInt();
        }
    }
    return m;
}

// Decodes every frame of `file` to `dir`/000.png, 001.png, ...; an error text or empty.
inline QString decodeFrames(const QString& file, const QString& dir) {
    const QString ffmpeg = ffmpegTool("ffmpeg");
    if (ffmpeg.isEmpty()) {
        return "ffmpeg not found (apt-get install ffmpeg)";
    }
    QDir().mkpath(dir);
    const CliRun r = runProgram(
        ffmpeg, {"-v", "error", "-i", file, "-start_number", "0", dir + "/%03d.png"}, 60000);
    return r.exitCode == 0 ? QString() : "ffmpeg " + file + ": " + r.err;
}

// Every file in `dir`, hidden ones too: what a movie left behind.
inline QStringList filesIn(const QString& dir) {
    return QDir(dir).entryList(QDir::Files | QDir::Hidden | QDir::NoDotAndDotDot);
}

inline QString framePng(const QString& dir, int k) {
    return dir + QString("/%1.png").arg(k, 3, 10, QChar('0'));
}

} // namespace lucent::test
