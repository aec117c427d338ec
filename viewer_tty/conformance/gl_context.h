// SPDX-License-Identifier: MIT
// gl_context.h — the process-wide EGL display and GL 3.3 core context behind gl_reference.h.
// Conventions: EGL_PLATFORM_SURFACELESS_MESA first, eglGetDisplay(EGL_DEFAULT_DISPLAY) second;
// the context is made current without any surface (EGL_KHR_surfaceless_context).
// Not here: any drawing (gl_reference.cpp).
#pragma once

#include <optional>
#include <string>

namespace pem::conformance {

// Makes the context current, creating it on first use; returns the failure reason, or nullopt.
// The outcome of the first call is remembered.
std::optional<std::string> EnsureGlContext();

}  // namespace pem::conformance
