// SPDX-License-Identifier: MIT
// fuzz_manifest.cpp — the pipeline's JSON files: the input as trace.json, manifest.json,
// infer.json and sample.json, each read by its one reader.
#include <cstddef>
#include <cstdint>

#include "base/input_error.h"
#include "pipeline/infer_report.h"
#include "pipeline/layout.h"
#include "pipeline/pem_manifest.h"
#include "pipeline/pem_set.h"
#include "pipeline/trace_manifest.h"
#include "tests/fuzz/fuzz_util.h"

namespace {

template <class F>
void Expect(const F& read) {
    try {
        read();
    } catch (const pem::base::InputError&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace pem::pipeline;
    const std::string dir = pem::fuzz::Dir();
    pem::fuzz::WriteInput(kTraceJson, data, size);
    pem::fuzz::WriteInput(kManifestJson, data, size);
    pem::fuzz::WriteInput(kInferJson, data, size);
    std::filesystem::create_directories(ViewDir(dir, 0));
    pem::fuzz::WriteInput(ViewDirName(0) + "/" + kSampleJson, data, size);
    Expect([&] { ReadTraceManifest(dir); });
    Expect([&] { LoadMapSet(ReadPemManifest(dir)); });
    Expect([&] { ReadInferJson(dir); });
    Expect([&] { ReadSampleJson(dir, 0); });
    return 0;
}
