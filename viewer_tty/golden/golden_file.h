// SPDX-License-Identifier: MIT
// golden_file.h — golden.json, the record of a golden directory: the profile the images were
// made with and what it models, pemref's version, and per test its PNG file, the SHA-256 of its
// RGBA8 pixels and of its input. The one writer beside the one reader.
//
//   GoldenRecord r = ReadGoldenFile("goldens");   r.tests[0].sha256
//
// Format `pemref_golden`, version 1. Errors: base::InputError naming golden.json.
// Not here: the images (PNG files beside it, base/png_io.h).
#pragma once

#include <string>
#include <vector>

namespace pem::golden {

struct GoldenEntry {
    std::string name, png;    // png: relative to the golden directory
    std::string sha256;       // of the RGBA8 pixels, rows top-down
    std::string inputSha256;  // of the input (case file; scene or PEM manifest + settings)
    int width = 0, height = 0;
};

struct GoldenRecord {
    std::string dir;  // not stored
    std::string profile, model, pemref;
    std::vector<GoldenEntry> tests;

    GoldenEntry* Find(const std::string& name);
    const GoldenEntry* Find(const std::string& name) const;
};

void WriteGoldenFile(const GoldenRecord& record);  // dir/golden.json, atomically
GoldenRecord ReadGoldenFile(const std::string& dir);

}  // namespace pem::golden
