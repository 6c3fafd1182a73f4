// lucent-cli compare A.png B.png
#include <QCommandLineParser>
#include <QFile>
#include <QTextStream>

#include <cmath>
#include <exception>
#include <filesystem>

#include "CliCommand.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"

namespace lucent::cli {

namespace {

std::filesystem::path toPath(const QString& arg) {
    return std::filesystem::path(QFile::encodeName(arg).toStdString());
}

QString sizeText(const ImageRGBA8& image) {
    return QString("%1x%2").arg(image.width).arg(image.height);
}

} // namespace

int runCompare(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(
        "Compares two PNG images of the same size and prints one line\n"
        "psnr_db=<x> ssim=<y>: PSNR in dB over R, G, B (peak 255; 'inf' when identical)\n"
        "and SSIM (Wang et al. 2004; 11x11 Gaussian window, sigma 1.5, K1 0.01, K2 0.03)\n"
        "on Rec. 601 luminance. Alpha is ignored.");
    parser.addPositionalArgument("A.png", "the first image");
    parser.addPositionalArgument("B.png", "the second image, the same size as the first");
    parser.addHelpOption();
    QTextStream err(stderr);
    if (!parser.parse(args)) {
        err << "lucent-cli compare: " << parser.errorText() << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        QTextStream(stdout) << parser.helpText();
        return kOk;
    }
    const QStringList positional = parser.positionalArguments();
    if (positional.size() != 2) {
        err << "lucent-cli compare: expected two PNG files, A.png and B.png\n" << parser.helpText();
        return kUsage;
    }
    try {
        const ImageRGBA8 a = readPng(toPath(positional[0]));
        const ImageRGBA8 b = readPng(toPath(positional[1]));
        if (a.width != b.width || a.height != b.height) {
            err << "lucent-cli compare: the images differ in size: " << positional[0] << " is "
                << sizeText(a) << ", " << positional[1] << " is " << sizeText(b) << "\n";
            return kBadInput;
        }
        if (a.width < kSsimWindow || a.height < kSsimWindow) {
            err << "lucent-cli compare: " << positional[0] << " and " << positional[1] << " are "
                << sizeText(a) << "; SSIM needs at least " << kSsimWindow << "x" << kSsimWindow
                << " pixels\n";
            return kBadInput;
        }
        const double p = psnr(a, b);
        const double s = ssim(a, b);
        QTextStream(stdout) << "psnr_db="
                            << (std::isinf(p) ? QString("inf") : QString::number(p, 'f', 2))
                            << " ssim=" << QString::number(s, 'f', 4) << "\n";
    } catch (const std::exception& e) {
        err << "lucent-cli compare: " << e.what() << "\n";
        return kBadInput;
    }
    return kOk;
}

} // namespace lucent::cli
