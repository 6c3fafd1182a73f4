#pragma once

#include <QStringList>

// Exit status of every lucent-cli command: 0 ok, 2 usage, 3 nothing loadable or bad input.
namespace lucent::cli {

constexpr int kOk = 0;
constexpr int kUsage = 2;
constexpr int kBadInput = 3;
constexpr int kNetwork = 4; // a PACS, a render server or the network failed

// Each takes the arguments after the command name, with the program name first.
int runInfo(const QStringList& args);
int runConvert(const QStringList& args);
int runCompare(const QStringList& args);
int runRender(const QStringList& args);
int runPacs(const QStringList& args); // exit 4: the PACS or the network failed
int runBench(const QStringList& args);

} // namespace lucent::cli
