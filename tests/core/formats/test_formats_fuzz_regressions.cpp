// Inputs that the volume-format harnesses (fuzz/) found, each once a runaway
// allocation (fuzz-regressions/README.md says which), read as the loader reads
// them: each must end in a LoadError that names the file and what is wrong.
#include <QTest>

#include <filesystem>
#include <string>

#include "core/formats/MetaImage.h"
#include "core/io/LoadControl.h"

namespace fs = std::filesystem;
using namespace lucent;

class TestFormatsFuzzRegressions : public QObject {
    Q_OBJECT

private slots:
    void metaImageLargerThanItsCompressedDataIsRefusedBeforeAllocating() {
        const fs::path file = fs::path(LUCENT_SOURCE_DIR) /
                              "tests/core/formats/fuzz-regressions/"
                              "metaimage-dimsize-beyond-compressed-data.mha";
        try {
            (void)readMetaImage(file);
            QFAIL("expected LoadError");
        } catch (const LoadError& e) {
            const QString what = e.what();
            QVERIFY2(what.startsWith(QString::fromStdString(file.string())), e.what());
            QVERIFY2(what.contains("CompressedData: ") && what.contains("cannot inflate to the "),
                     e.what());
        }
    }
};

QTEST_APPLESS_MAIN(TestFormatsFuzzRegressions)
#include "test_formats_fuzz_regressions.moc"
