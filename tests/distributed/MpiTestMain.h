#pragma once
// main() of a Qt Test suite that runs under mpirun: MPI for the whole run,
// every rank runs every test function (they hold collectives), rank 0 reports,
// and the job fails when any rank failed.

#include <QCoreApplication>
#include <QTest>

#include <vector>

#include "render/distributed/Communicator.h"
#include "render/distributed/MpiSession.h"

#define LUCENT_MPI_TEST_MAIN(TestClass)                                                            \
    int main(int argc, char** argv) {                                                              \
        lucent::MpiSession mpi;                                                                    \
        QCoreApplication app(argc, argv);                                                          \
        TestClass test;                                                                            \
        QStringList args = QCoreApplication::arguments();                                          \
        if (mpi.rank() != 0) {                                                                     \
            args << "-silent";                                                                     \
        }                                                                                          \
        const int failed = QTest::qExec(&test, args);                                              \
        const lucent::Communicator comm = lucent::Communicator::world();                           \
        return comm.allMax(double(failed)) > 0.0 ? 1 : 0;                                          \
    }
