// SPDX-License-Identifier: MIT
// fuzz_util.h — what the harnesses share: the bytes written to a file of a given name in a
// private temporary directory (the loaders take paths), and the contract every loader keeps:
// bad input throws base::InputError (one line naming the file); anything else escaping — or a
// crash, a hang, a sanitizer report — is a finding.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace pem::fuzz {

inline std::string Dir() {
    static const std::string dir = [] {
        const auto d =
            std::filesystem::temp_directory_path() / ("pemref_fuzz_" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d.string();
    }();
    return dir;
}

inline std::string WriteInput(const std::string& name, const uint8_t* data, size_t size) {
    const std::string path = Dir() + "/" + name;
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path;
}

}  // namespace pem::fuzz
