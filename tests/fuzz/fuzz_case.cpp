// SPDX-License-Identifier: MIT
// fuzz_case.cpp — raster case files (viewer_tty/conformance/case_file.h), then the parsed frame
// rendered at most 64×64 (so a case that loads is also drawn).
#include <cstddef>
#include <cstdint>
#include <string>

#include "base/input_error.h"
#include "raster/render.h"
#include "viewer_tty/conformance/case_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        const pem::raster::Frame f = pem::conformance::ParseCaseJson(
            std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
        if (f.width <= 64 && f.height <= 64)
            pem::raster::Render(pem::raster::PreparedFrame(f), pem::raster::RenderOptions{});
    } catch (const pem::base::InputError&) {
    }
    return 0;
}
