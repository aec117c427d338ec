// SPDX-License-Identifier: MIT
// exr_header.h — what every reader of OpenEXR files here (trace/image.h, infer/pem_file.h)
// checks before OpenEXR's C++ reader opens a file. That reader trusts the header: it allocates
// an attribute's claimed size and tables sized by the data window before it reads them (1.7 GB
// for a 44-byte file the fuzzer made). CheckExrHeader parses the header with OpenEXRCore, the
// library's validating C parser, with side limits, and bounds every data window by
// kMaxExrPixels; CheckExrSize is the window rule alone. Both throw
// pem::base::InputError("<path>: <cause>").
// Not here: reading pixels (OpenEXR's C++ API, in trace/ and infer/).
#pragma once

#include <cstdint>
#include <string>

namespace pem::base {

inline constexpr int kMaxExrSide = 1 << 16;
inline constexpr int64_t kMaxExrPixels = int64_t{1} << 27;  // a 4096² cube map: 4096 x 24576

void CheckExrHeader(const std::string& path);
void CheckExrSize(const std::string& path, int64_t width, int64_t height);

}  // namespace pem::base
