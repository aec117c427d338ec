// SPDX-License-Identifier: MIT
// case_file.h — read and write raster cases (`gl_ref_case/1` plus pemref's superset: 2D textures,
// 0..2 texture units per pass; depth buffer and depth tests; docs/raster-case-format.md) as
// pem::raster::Frame.
// Conventions: Frame::textures = all cube maps (file order), then all 2D textures; every float is
// exact (JSON number -> double -> float, or a strtod string); errors throw pem::base::InputError.
// Not here: rendering or hashing (raster/, gl_reference.h, sha256.h).
#pragma once

#include <string>

#include "base/input_error.h"
#include "raster/frame.h"

namespace pem::conformance {

// Reads and validates a case file. Throws base::InputError("<path>: <json key>: <cause>") on any
// problem: unreadable file, invalid JSON, missing/mistyped key, bad value, bad sizes or indices.
raster::Frame LoadCaseFile(const std::string& path);

// Same, from JSON text; `path` is used only in error messages.
raster::Frame ParseCaseJson(const std::string& text, const std::string& path);

// Writes `frame` as a case with explicit base64 texels, every key spelled out, and vertices as
// exact numbers. ParseCaseJson(CaseToJson(f)) == f when f is canonical: cube maps before 2D
// textures, unused unit slots (texture index, coordinates) zero, a disabled BlendState default,
// cube samplers with default wrap modes and 2D samplers with `seamless` true (those fields have
// no meaning in the format and are not written), depth tests only in frames with a depth buffer.
std::string CaseToJson(const raster::Frame& frame);

}  // namespace pem::conformance
