#include "DistributedRender.h"

#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QTextStream>

#include <optional>

#include "CliCommand.h"
#include "FrameSeries.h"
#include "RenderFlags.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "core/scene/DefaultPreset.h"

#if LUCENT_DISTRIBUTED
#include "render/distributed/DistributedRenderer.h"
#include "render/distributed/MpiSession.h"
#include "render/distributed/RankAgreement.h"
#endif

namespace lucent::cli {

#if !LUCENT_DISTRIBUTED

int runDistributedRender(const QCommandLineParser&) {
    QTextStream(stderr) << "lucent-cli render: --distributed: this build has no distributed "
                           "renderer (configure with LUCENT_DISTRIBUTED=ON, which needs Open MPI "
                           "and IceT: packaging/install-deps.sh)\n";
    return kUsage;
}

#else

namespace {

// Flags the distributed path does not take, with the reason.
const char* refused(const QCommandLineParser& p) {
    if (p.value("backend").startsWith("ws")) {
        return "--distributed renders here, not on a render server (--backend ws://)";
    }
    if (p.value("backend") != "cpu" && p.value("backend") != "gl") {
        return "--distributed renders with --backend cpu or gl on every rank";
    }
    if (p.isSet("quality")) {
        return "--quality measures one process's front; give --step and --interp with "
               "--distributed";
    }
    return nullptr;
}

// The description the flags ask for (as the local path: the table's options,
// the transfer function, the options again).
RenderDescription describe(const QCommandLineParser& p, const std::string& modality) {
    RenderDescription d;
    applyRenderFlags(p, d);
    if (p.isSet("preset") && p.isSet("tf")) {
        throw std::invalid_argument("--preset and --tf exclude each other");
    }
    if (p.isSet("tf")) {
        d.transferFunction = readTransferFunction(p.value("tf").toStdString());
    } else {
        d.transferFunction = loadPreset(p.isSet("preset") ? p.value("preset").toStdString()
                                                          : defaultPresetName(modality, d.mode));
    }
    applyRenderFlags(p, d);
    return d;
}

} // namespace

int runDistributedRender(const QCommandLineParser& parser) {
    QTextStream err(stderr);
    if (const char* why = refused(parser)) {
        err << "lucent-cli render: " << why << "\n";
        return kUsage;
    }
    bool repeatOk = true;
    const int repeat = parser.isSet("repeat") ? parser.value("repeat").toInt(&repeatOk) : 1;
    if (!repeatOk || repeat < 1 || repeat > 10000) {
        err << "lucent-cli render: --repeat must be between 1 and 10000\n";
        return kUsage;
    }
    const MpiSession mpi;
    const Communicator comm = Communicator::world();
    const bool root = comm.rank() == 0;
    // Only rank 0 speaks: every rank knows every failure (RankAgreement.h).
    auto fail = [&](const std::string& message, int status) {
        if (root) {
            err << "lucent-cli render: " << QString::fromStdString(message) << "\n";
        }
        return status;
    };

    QElapsedTimer timer;
    timer.start();
    std::optional<SeriesEntry> entry;
    RenderDescription desc;
    try {
        const std::string path = parser.positionalArguments()[0].toStdString();
        const std::string series = parser.value("series").toStdString();
        onEveryRank(comm, "scanning " + path, [&] {
            const Catalog catalog = scanPath(path);
            const SeriesEntry* e = series.empty() ? catalog.defaultEntry() : catalog.find(series);
            if (e == nullptr) {
                throw LoadError(series.empty() ? path + " holds no loadable volume"
                                               : "no series '" + series + "' under " + path);
            }
            entry = *e;
        });
    } catch (const DistributedError& e) {
        return fail(e.what(), kBadInput);
    }
    try {
        desc = describe(parser, entry->modality);
        desc.validate();
    } catch (const std::exception& e) {
        return fail(e.what(), kUsage);
    }

    try {
        const RendererKind kind = parseRendererKind(parser.value("backend").toStdString());
        DistributedRenderer renderer(comm, loadPart(comm, *entry, desc, desc.sampling.brickSize),
                                     kind);
        if (kind == RendererKind::Gl && renderer.backend() != "gl" && root) {
            err << "lucent-cli render: the GL backend is not available on every rank; those "
                   "ranks render on the CPU\n";
        }
        const double loadMs = double(timer.nsecsElapsed()) / 1e6;
        const FrameSeries series = renderFrames(renderer, desc, repeat);
        if (root) {
            writePng(series.first.image, parser.value("output").toStdString());
        }
        if (root && parser.isSet("stats")) {
            QTextStream out(stdout);
            const PartReadStats& read = renderer.part().read;
            out << seriesStats(loadMs, series) << " frames=" << repeat
                << " backend=" << QString::fromStdString(renderer.backend())
                << " distributed=1 rank0_slab_reading=" << (read.slabs ? 1 : 0)
                << " rank0_files_read=" << read.files.size();
            // The last frame's figures: steady state.
            for (const auto& [key, value] : series.lastDetails) {
                out << " " << QString::fromStdString(key) << "=" << QString::fromStdString(value);
            }
            out << "\n";
        }
    } catch (const DistributedError& e) {
        return fail(e.what(), kBadInput);
    } catch (const std::invalid_argument& e) {
        return fail(e.what(), kUsage);
    } catch (const std::exception& e) {
        // Not agreed among ranks (a local write): end the job rather than leave ranks waiting.
        comm.abort(std::string("lucent-cli render: ") + e.what(), kBadInput);
    }
    return kOk;
}

#endif

} // namespace lucent::cli
