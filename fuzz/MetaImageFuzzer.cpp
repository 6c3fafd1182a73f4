// fuzz_metaimage: one input is a MetaImage file with its voxels inside
// (.mha, ElementDataFile = LOCAL). Its header is read, then the whole volume,
// then (uncompressed data) its first slice alone, as a distributed rank reads
// it. Bad input must end in a LoadError naming the file.
#include <cstddef>
#include <cstdint>

#include "core/formats/MetaImage.h"
#include "core/io/LoadControl.h"
#include "fuzz/ScratchFile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static lucent::fuzz::ScratchFile file("input.mha");
    const std::string& path = file.write(data, size);
    try {
        (void)lucent::readMetaImageHeader(path);
        (void)lucent::readMetaImage(path);
        if (lucent::metaImageHasSliceRanges(path)) {
            (void)lucent::readMetaImageSlices(path, 0, 1);
        }
    } catch (const lucent::LoadError&) {
    }
    return 0;
}
