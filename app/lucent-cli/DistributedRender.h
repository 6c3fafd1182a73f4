#pragma once
// lucent-cli render PATH -o OUT.png --distributed [options], under mpirun: every
// rank reads and renders its part of the volume, IceT composites, rank 0
// writes the image (docs/distributed.md).

class QCommandLineParser;

namespace lucent::cli {

// The render command's --distributed path, once its flags are parsed. Returns
// the exit status (every rank returns the same).
int runDistributedRender(const QCommandLineParser& parser);

} // namespace lucent::cli
