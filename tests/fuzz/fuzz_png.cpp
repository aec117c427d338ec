// SPDX-License-Identifier: MIT
// fuzz_png.cpp — PNG files (base/png_io.h ReadPng: golden images, `pemref golden compare`).
#include <cstddef>
#include <cstdint>

#include "base/input_error.h"
#include "base/png_io.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        const pem::base::Image8 img =
            pem::base::ReadPng(pem::fuzz::WriteInput("i.png", data, size));
        if (img.rgba.size() != size_t(img.width) * size_t(img.height) * 4) __builtin_trap();
    } catch (const pem::base::InputError&) {
    }
    return 0;
}
