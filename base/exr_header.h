// SPDX-License-Identifier: MIT
// exr_header.h — what every reader of OpenEXR files here (trace/image.h, infer/pem_file.h)
// checks around OpenEXR, which trusts a file's header: the magic number and header attributes
// that end inside the file, before OpenEXR opens it (it allocates an attribute's claimed size
// before reading it: 1.7 GB for a 44-byte file the fuzzer made); once open, a data window of at
// most kMaxExrPixels pixels. Both throw pem::base::InputError("<path>: <cause>").
// Not here: reading pixels (OpenEXR, in trace/ and infer/).
#pragma once

#include <cstdint>
#include <string>

namespace pem::base {

inline constexpr int64_t kMaxExrPixels = int64_t{1} << 26;  // 8192 x 8192

void CheckExrHeader(const std::string& path);
void CheckExrSize(const std::string& path, int64_t width, int64_t height);

}  // namespace pem::base
