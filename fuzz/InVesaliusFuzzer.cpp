// fuzz_inv3: one input is an InVesalius 3 project: a tar archive (gzipped or
// not: zlib reads both) holding main.plist and the image matrix. Its header
// (the archive walk and the plist) is read, then the volume. Bad input must end
// in a LoadError naming the file and the key or entry at fault.
#include <cstddef>
#include <cstdint>

#include "core/formats/InVesaliusProject.h"
#include "core/io/LoadControl.h"
#include "fuzz/ScratchFile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static lucent::fuzz::ScratchFile file("input.inv3");
    const std::string& path = file.write(data, size);
    try {
        (void)lucent::readInVesaliusHeader(path);
        (void)lucent::readInVesalius(path);
    } catch (const lucent::LoadError&) {
    }
    return 0;
}
