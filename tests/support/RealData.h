#pragma once
// The real DICOM of ../shared/data (its README says what each set is for).
// A test that needs a set skips with a clear message when it is missing, so a
// fresh clone without ../shared still builds and passes its other tests.

#include <QString>
#include <QTest>

#include <filesystem>

namespace lucent::test {

inline const std::filesystem::path kRealData = LUCENT_TEST_DATA_DIR;

} // namespace lucent::test

#define REQUIRE_DATA(sub)                                                                          \
    if (!std::filesystem::exists(lucent::test::kRealData / (sub)))                                 \
    QSKIP(                                                                                         \
        qPrintable(QString("real test data not found: %1 (see ../shared/data/README.md)")          \
                       .arg(QString::fromStdString((lucent::test::kRealData / (sub)).string()))))
