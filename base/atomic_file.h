// SPDX-License-Identifier: MIT
// atomic_file.h — every output file of pemref appears whole or not at all.
//
//   WriteTextAtomic("out/trace.json", text);
//   WriteAtomically("out/a.exr", [&](const std::string& tmp) { WriteExrTo(tmp, image); });
//
// Conventions: the data goes to `<path>.tmp.<pid>` (TemporaryPath) next to the target, which is
// renamed over `path` only when the writer returned; if the writer throws, the temporary file is
// removed and a base::InputError `<path>: <cause>` is thrown. A killed process may leave
// temporaries behind: RemoveTemporaries clears them from a directory tree (resumable jobs call
// it before they start). Not here: fsync (a crash of the machine may lose the last files).
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace pem::base {

// `<path>.tmp.<pid>`.
std::string TemporaryPath(const std::string& path);

// write(tmp) writes the whole file at tmp; then tmp is renamed over path.
void WriteAtomically(const std::string& path,
                     const std::function<void(const std::string& tmp)>& write);

// The text as the whole file.
void WriteTextAtomic(const std::string& path, const std::string& text);

// Several files (path, text) published together: every temporary file is written before the
// first rename, so a failure leaves none of them changed.
void WriteTextsAtomic(const std::vector<std::pair<std::string, std::string>>& files);

// A directory written whole: write(tmp) fills the directory `<path>.tmp.<pid>`, which then takes
// the place of `path`. `path` must be absent, empty or hold `marker` (a previous run's output,
// replaced); otherwise, before any work, InputError. If write throws, the temporary directory is
// removed and the error passes on (as InputError naming path when it was another exception).
void WriteDirectoryAtomically(const std::string& path, const std::string& marker,
                              const std::function<void(const std::string& tmp)>& write);

// Removes every regular file under dir whose name holds ".tmp" (what killed runs left).
void RemoveTemporaries(const std::string& dir);

}  // namespace pem::base
