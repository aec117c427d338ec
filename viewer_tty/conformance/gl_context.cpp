// SPDX-License-Identifier: MIT
// gl_context.cpp — EGL bring-up: display (surfaceless platform, then default), desktop GL API,
// a 3.3 core context made current with no surface; optional retry with Mesa's software driver.
// Conventions: every failure is a one-line reason string; nothing throws from here.
// Not here: GL object management or drawing.
#include "viewer_tty/conformance/gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace pem::conformance {

namespace {

struct EglState {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
};

bool HasClientExtension(const char* name) {
    const char* list = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    return list && std::strstr(list, name) != nullptr;
}

std::string EglErrorText(const char* what) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(eglGetError()));
    return std::string(what) + " failed (EGL error " + code + ")";
}

// The surfaceless Mesa display if available, else the default display; initialised.
std::optional<std::string> OpenDisplay(EglState* egl) {
    if (HasClientExtension("EGL_MESA_platform_surfaceless")) {
        auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
            eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (getPlatformDisplay)
            egl->display =
                getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (egl->display != EGL_NO_DISPLAY && eglInitialize(egl->display, nullptr, nullptr))
            return std::nullopt;
    }
    egl->display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (egl->display == EGL_NO_DISPLAY) return "no EGL display (surfaceless or default)";
    if (!eglInitialize(egl->display, nullptr, nullptr)) return EglErrorText("eglInitialize");
    return std::nullopt;
}

// A GL 3.3 core context, current without a surface.
std::optional<std::string> CreateContext(EglState* egl) {
    if (!eglBindAPI(EGL_OPENGL_API)) return EglErrorText("eglBindAPI(EGL_OPENGL_API)");
    // Any surface type (the default, EGL_WINDOW_BIT, excludes surfaceless pbuffer-only configs).
    const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0,
                                    EGL_NONE};
    EGLConfig config = nullptr;
    EGLint numConfigs = 0;
    if (!eglChooseConfig(egl->display, configAttribs, &config, 1, &numConfigs) || numConfigs < 1)
        return "no EGL config with EGL_OPENGL_BIT";
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     3,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     3,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
    egl->context = eglCreateContext(egl->display, config, EGL_NO_CONTEXT, contextAttribs);
    if (egl->context == EGL_NO_CONTEXT) return EglErrorText("eglCreateContext(GL 3.3 core)");
    if (!eglMakeCurrent(egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl->context))
        return EglErrorText("eglMakeCurrent(no surface)");
    return std::nullopt;
}

std::optional<std::string> TryInit(EglState* egl) {
    if (auto error = OpenDisplay(egl)) return error;
    if (auto error = CreateContext(egl)) {
        if (egl->context != EGL_NO_CONTEXT) eglDestroyContext(egl->display, egl->context);
        eglTerminate(egl->display);
        *egl = EglState{};
        return error;
    }
    return std::nullopt;
}

std::optional<std::string> InitOnce() {
    EglState egl;
    std::optional<std::string> error = TryInit(&egl);
    if (error && std::getenv("LIBGL_ALWAYS_SOFTWARE") == nullptr) {
        // No usable driver: retry with Mesa's software rasterizer (llvmpipe).
        setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
        eglReleaseThread();
        if (!TryInit(&egl)) return std::nullopt;
        return *error + " (also with LIBGL_ALWAYS_SOFTWARE=1)";
    }
    return error;
}

}  // namespace

std::optional<std::string> EnsureGlContext() {
    static const std::optional<std::string> result = InitOnce();
    return result;
}

}  // namespace pem::conformance
