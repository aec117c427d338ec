// SPDX-License-Identifier: MIT
// layout.cpp — file and directory names (layout.h).
#include "pipeline/layout.h"

#include <cstdio>
#include <filesystem>

#include "base/input_error.h"
#include "runtime/lens_group_em.h"

namespace pem::pipeline {

std::string ViewDirName(int view) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "view_%03d", view);
    return buf;
}

std::string ViewDir(const std::string& dir, int view) {
    return dir + "/" + ViewDirName(view);
}

std::string GroupSubdir(int view, int group) {
    return ViewDirName(view) + "/group_" + std::to_string(group);
}

std::string GroupDir(const std::string& dir, int view, int group) {
    return dir + "/" + GroupSubdir(view, group);
}

std::string FrameImagePath(const std::string& traceDir, int view, const std::string& name) {
    return ViewDir(traceDir, view) + "/" + name + ".exr";
}

std::string GroupImagePath(const std::string& traceDir, int view, int group,
                           const std::string& name) {
    return GroupDir(traceDir, view, group) + "/" + name + ".exr";
}

std::string GroupSampleImagePath(const std::string& traceDir, int view, int group,
                                 const std::string& name) {
    return GroupDir(traceDir, view, group) + "/samples/" + name + ".exr";
}

std::string LayerImageName(int layer, int term) {
    return "layer_" + std::to_string(layer) + "_" + runtime::TermName(term);
}

std::string MapFile(int view, int group, const std::string& name) {
    return GroupSubdir(view, group) + "/" + name + ".exr";
}

std::string MapPath(const std::string& pemDir, int view, int group, const std::string& name) {
    return pemDir + "/" + MapFile(view, group, name);
}

std::string MapStem(const std::string& pemDir, int view, int group, const std::string& name) {
    return GroupDir(pemDir, view, group) + "/" + name;
}

std::string LayerMapName(int layer) {
    return "layer_" + std::to_string(layer);
}

std::string SampleJsonPath(const std::string& pemDir, int view) {
    return ViewDir(pemDir, view) + "/" + kSampleJson;
}

std::string BakeTraceDir(const std::string& bakeDir) {
    return bakeDir + "/trace";
}

std::string BakePemDir(const std::string& bakeDir) {
    return bakeDir + "/pem";
}

std::string BakeJsonPath(const std::string& bakeDir) {
    return bakeDir + "/" + kBakeJson;
}

void CheckInside(const std::string& dir, const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path root = fs::weakly_canonical(dir, ec);
    const fs::path real = fs::weakly_canonical(path, ec);
    if (ec) throw base::InputError(path, "cannot resolve the path: " + ec.message());
    const fs::path rel = real.lexically_relative(root);
    if (rel.empty() || *rel.begin() == "..")
        throw base::InputError(path, "leads outside " + dir + " (" + real.string() + ")");
}

std::string PreviewPath(const std::string& exrPath) {
    const std::string ext = ".exr";
    if (exrPath.size() >= ext.size() &&
        exrPath.compare(exrPath.size() - ext.size(), ext.size(), ext) == 0)
        return exrPath.substr(0, exrPath.size() - ext.size()) + ".png";
    return exrPath + ".png";
}

}  // namespace pem::pipeline
