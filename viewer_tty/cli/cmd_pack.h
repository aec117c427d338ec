// SPDX-License-Identifier: MIT
// cmd_pack.h — `pemref pack` and `pemref unpack`: a PEM directory as one compressed file and
// back (pipeline/pem_pack.h). `render` and `view` read packed PEMs directly.
//   pemref pack PEM_DIR --out FILE [--codec zstd|xz] [--max-error E] [--ratio R] [--quiet]
//   pemref unpack FILE --out PEM_DIR [--threads N]
// --max-error 0 (the default) is lossless: the pack renders byte-identically to the directory;
// E > 0 keeps every 8-bit texel within E of the directory's; --ratio R codes the levels of faces
// ≥ 8 wide by JPEG 2000 at R:1 (lossy; R = 1 lossless). pack prints one line: bytes per sample
// and the ratios against the directory's float EXR and 8-bit PNG maps.
// Errors: one line, exit 1 (main.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace pem::cli {

void AddPackCommands(CLI::App& app);
int RunPackCommand();
int RunUnpackCommand();

}  // namespace pem::cli
