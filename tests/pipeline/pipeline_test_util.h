// SPDX-License-Identifier: MIT
// pipeline_test_util.h — what the pipeline tests share: the bundled scenes, fresh temporary
// directories, a directory tree's bytes, the error a reader gives.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "base/input_error.h"

namespace pem::pipeline {

inline const std::string kRoot = PEM_SOURCE_DIR;
inline const std::string kHybrid = kRoot + "/data/scenes/hybrid_glass_teapot.gltf";
inline const std::string kMirrorSphere = kRoot + "/data/scenes/mirror_sphere.gltf";

namespace fs = std::filesystem;

// Every regular file under dir, by relative path.
inline std::map<std::string, std::string> ReadTree(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (!e.is_regular_file()) continue;
        std::ifstream f(e.path(), std::ios::binary);
        files[fs::relative(e.path(), dir).string()] =
            std::string(std::istreambuf_iterator<char>(f), {});
    }
    return files;
}

// The one-line error a reader gives, or "" when it reads the file.
template <class F>
std::string ErrorOf(const F& read) {
    try {
        read();
    } catch (const base::InputError& e) {
        return e.what();
    }
    return "";
}

// An empty directory of its own under the temporary directory.
inline fs::path FreshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() /
                         ("pemref_pipeline_test_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

}  // namespace pem::pipeline
