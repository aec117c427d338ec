// SPDX-License-Identifier: MIT
// fuzz_exr.cpp — OpenEXR files: trace images and environment maps (trace::ReadExr) and
// inferred cube maps (infer::ReadEnvMapExr, which the PEM set wraps into base::InputError).
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "base/input_error.h"
#include "infer/pem_file.h"
#include "tests/fuzz/fuzz_util.h"
#include "trace/image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = pem::fuzz::WriteInput("i.exr", data, size);
    try {
        pem::trace::ReadExr(path);
    } catch (const pem::base::InputError&) {
    }
    try {
        pem::infer::ReadEnvMapExr(path);
    } catch (const std::exception&) {  // OpenEXR's Iex exceptions derive from it
    }
    return 0;
}
