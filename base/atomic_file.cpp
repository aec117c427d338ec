// SPDX-License-Identifier: MIT
// atomic_file.cpp — temporary file, then rename (atomic_file.h).
#include "base/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <stdexcept>

#include "base/input_error.h"

namespace pem::base {
namespace {

void WriteText(const std::string& tmp, const std::string& text) {
    FILE* file = std::fopen(tmp.c_str(), "wb");
    if (!file) throw std::runtime_error(std::string("cannot create: ") + std::strerror(errno));
    std::string error;
    if (std::fwrite(text.data(), 1, text.size(), file) != text.size()) error = std::strerror(errno);
    if (std::fflush(file) != 0 && error.empty()) error = std::strerror(errno);
    if (std::fclose(file) != 0 && error.empty()) error = std::strerror(errno);
    if (!error.empty()) throw std::runtime_error("cannot write: " + error);
}

void Rename(const std::string& tmp, const std::string& path) {
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
        throw InputError(path, std::string("cannot rename: ") + std::strerror(errno));
}

}  // namespace

std::string TemporaryPath(const std::string& path) {
    return path + ".tmp." + std::to_string(::getpid());
}

void WriteAtomically(const std::string& path,
                     const std::function<void(const std::string& tmp)>& write) {
    const std::string tmp = TemporaryPath(path);
    try {
        write(tmp);
        Rename(tmp, path);
    } catch (const InputError&) {
        std::remove(tmp.c_str());
        throw;
    } catch (const std::exception& e) {
        std::remove(tmp.c_str());
        throw InputError(path, e.what());
    }
}

void WriteDirectoryAtomically(const std::string& path, const std::string& marker,
                              const std::function<void(const std::string& tmp)>& write) {
    namespace fs = std::filesystem;
    // Step 1: path may be replaced only if it is absent, empty or a previous output.
    std::error_code ec;
    if (fs::exists(path, ec) && !(fs::is_directory(path, ec) &&
                                  (fs::is_empty(path, ec) || fs::exists(path + "/" + marker, ec))))
        throw InputError(path, "exists and is not an earlier output (no " + marker +
                                   "): choose another directory");
    // Step 2: the work, in a fresh temporary directory.
    const std::string tmp = TemporaryPath(path);
    fs::remove_all(tmp, ec);
    try {
        if (!fs::create_directories(tmp, ec) && ec)
            throw InputError(path, "cannot create a directory beside it: " + ec.message());
        write(tmp);
        // Step 3: the old output out, the new one in.
        fs::remove_all(path, ec);
        if (ec) throw InputError(path, "cannot remove the earlier output: " + ec.message());
        Rename(tmp, path);
    } catch (const InputError&) {
        fs::remove_all(tmp, ec);
        throw;
    } catch (const std::exception& e) {
        fs::remove_all(tmp, ec);
        throw InputError(path, e.what());
    }
}

void WriteTextAtomic(const std::string& path, const std::string& text) {
    WriteAtomically(path, [&](const std::string& tmp) { WriteText(tmp, text); });
}

void WriteTextsAtomic(const std::vector<std::pair<std::string, std::string>>& files) {
    // Step 1: every temporary file; on a failure remove those already written.
    std::vector<std::string> tmps;
    for (const auto& [path, text] : files) {
        tmps.push_back(TemporaryPath(path));
        try {
            WriteText(tmps.back(), text);
        } catch (const std::exception& e) {
            for (const std::string& t : tmps) std::remove(t.c_str());
            throw InputError(path, e.what());
        }
    }
    // Step 2: publish; a failed rename removes the temporaries not yet published.
    for (size_t i = 0; i < files.size(); ++i) {
        try {
            Rename(tmps[i], files[i].first);
        } catch (...) {
            for (size_t k = i; k < tmps.size(); ++k) std::remove(tmps[k].c_str());
            throw;
        }
    }
}

void RemoveTemporaries(const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(dir, ec)) return;
    std::vector<fs::path> stale;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir, ec))
        if (e.is_regular_file() && e.path().filename().string().find(".tmp") != std::string::npos)
            stale.push_back(e.path());
    for (const fs::path& p : stale) fs::remove(p, ec);
}

}  // namespace pem::base
