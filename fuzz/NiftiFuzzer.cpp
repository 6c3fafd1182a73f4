// fuzz_nifti: one input is a NIfTI-1 single file (.nii; zlib reads a gzipped
// one the same way). Its header is read, then its first volume. Bad input must
// end in a LoadError naming the file.
#include <cstddef>
#include <cstdint>

#include "core/formats/Nifti.h"
#include "core/io/LoadControl.h"
#include "fuzz/ScratchFile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static lucent::fuzz::ScratchFile file("input.nii");
    const std::string& path = file.write(data, size);
    try {
        (void)lucent::readNiftiHeader(path);
        (void)lucent::readNifti(path);
    } catch (const lucent::LoadError&) {
    }
    return 0;
}
