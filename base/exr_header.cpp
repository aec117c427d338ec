// SPDX-License-Identifier: MIT
#include "base/exr_header.h"

#include <algorithm>
#include <fstream>
#include <iterator>

#include "base/input_error.h"

namespace pem::base {

void CheckExrHeader(const std::string& path) {
    // Step 1: the first 64 KiB (a header rarely needs more; then the whole file).
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw InputError(path, "cannot open file");
    const size_t total = static_cast<size_t>(in.tellg());
    std::string bytes(std::min<size_t>(total, size_t{1} << 16), '\0');
    in.seekg(0);
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    const auto needAll = [&] {
        if (bytes.size() == total) return false;
        bytes.resize(total);
        in.read(bytes.data() + (size_t{1} << 16), static_cast<std::streamsize>(total - (1u << 16)));
        return true;
    };
    if (total < 8 || bytes.compare(0, 4, "\x76\x2f\x31\x01") != 0)
        throw InputError(path, "not an OpenEXR file");
    // Step 2: attributes (name\0 type\0 int32 size, little-endian, value) until an empty name.
    size_t at = 8;
    const auto cString = [&] {
        size_t end = bytes.find('\0', at);
        while (end == std::string::npos && needAll()) end = bytes.find('\0', at);
        if (end == std::string::npos) throw InputError(path, "header ends early");
        const size_t length = end - at;
        at = end + 1;
        return length;
    };
    while (cString() != 0) {
        cString();  // the type name
        if (total - at < 4) throw InputError(path, "header ends early");
        if (bytes.size() - at < 4) needAll();
        uint32_t size = 0;
        for (int k = 3; k >= 0; --k)
            size = (size << 8) | static_cast<uint8_t>(bytes[at + static_cast<size_t>(k)]);
        at += 4;
        if (size > total - at) throw InputError(path, "a header attribute is longer than the file");
        at += size;
        if (at >= bytes.size()) needAll();
    }
}

void CheckExrSize(const std::string& path, int64_t width, int64_t height) {
    if (width < 1 || height < 1 || width > kMaxExrPixels / height)
        throw InputError(path, "data window " + std::to_string(width) + " x " +
                                   std::to_string(height) + " is empty or too large");
}

}  // namespace pem::base
