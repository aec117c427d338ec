// SPDX-License-Identifier: MIT
// fuzz_gltf.cpp — glTF scenes (trace/scene.h LoadScene): the input as .gltf (JSON with data URIs
// and sibling files) or, when it starts with "glTF", as .glb.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "base/input_error.h"
#include "tests/fuzz/fuzz_util.h"
#include "trace/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::string path = pem::fuzz::WriteInput(glb ? "s.glb" : "s.gltf", data, size);
    try {
        pem::trace::LoadScene(path);
    } catch (const pem::base::InputError&) {
    }
    return 0;
}
