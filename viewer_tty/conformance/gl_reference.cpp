// SPDX-License-Identifier: MIT
// gl_reference.cpp — RenderWithGl: upload textures, build one program per pass shape, draw every
// pass into an RGBA8 or RGBA32F renderbuffer (with a depth renderbuffer when the frame has one),
// read back, flip rows to top-down.
// Conventions: attribute locations 0 a_pos, 1 a_c0, 2 a_c1, 3 a_col; sampler u<k> on texture
// unit k; vertex buffers hold the case's interleaved floats (4 + 3*units + 4 per vertex).
// Not here: context creation (gl_context.cpp); no stencil, scissor, culling or dither.
#include "viewer_tty/conformance/gl_reference.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <chrono>
#include <map>
#include <tuple>

#include "viewer_tty/conformance/gl_context.h"

namespace pem::conformance {

namespace {

using raster::Frame;
using raster::Pass;
using raster::Texture;
using raster::TextureKind;

// GL objects of one RenderWithGl call, deleted at the end (also on exceptions).
struct GlObjects {
    std::vector<GLuint> textures, buffers, vertexArrays, programs;
    GLuint framebuffer = 0, renderbuffer = 0, depthRenderbuffer = 0;
    ~GlObjects() {
        glDeleteTextures(GLsizei(textures.size()), textures.data());
        glDeleteBuffers(GLsizei(buffers.size()), buffers.data());
        glDeleteVertexArrays(GLsizei(vertexArrays.size()), vertexArrays.data());
        for (GLuint p : programs) glDeleteProgram(p);
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteRenderbuffers(1, &renderbuffer);
        glDeleteRenderbuffers(1, &depthRenderbuffer);
    }
};

void CheckGl(const char* step) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR)
        throw GlError(std::string(step) + ": GL error " + std::to_string(error));
}

void RequireContext() {
    if (auto reason = EnsureGlContext()) throw GlError("OpenGL unavailable: " + *reason);
}

// Textures ------------------------------------------------------------------------------------

GLint MinFilterEnum(const raster::SamplerState& s) {
    const bool linear = s.minFilter == raster::Filter::Linear;
    switch (s.mipFilter) {
        case raster::MipFilter::None:
            return linear ? GL_LINEAR : GL_NEAREST;
        case raster::MipFilter::Nearest:
            return linear ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
        case raster::MipFilter::Linear:
            return linear ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR;
    }
    return GL_LINEAR;
}

GLint WrapEnum(raster::Wrap wrap) {
    switch (wrap) {
        case raster::Wrap::ClampToEdge:
            return GL_CLAMP_TO_EDGE;
        case raster::Wrap::Repeat:
            return GL_REPEAT;
        case raster::Wrap::MirroredRepeat:
            return GL_MIRRORED_REPEAT;
    }
    return GL_CLAMP_TO_EDGE;
}

void SetSamplerParameters(GLenum target, const Texture& tex) {
    const raster::SamplerState& s = tex.sampler;
    const bool cube = tex.kind == TextureKind::Cube;
    glTexParameteri(target, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(target, GL_TEXTURE_MAX_LEVEL, tex.NumLevels() - 1);
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, MinFilterEnum(s));
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER,
                    s.magFilter == raster::Filter::Linear ? GL_LINEAR : GL_NEAREST);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, cube ? GL_CLAMP_TO_EDGE : WrapEnum(s.wrapS));
    glTexParameteri(target, GL_TEXTURE_WRAP_T, cube ? GL_CLAMP_TO_EDGE : WrapEnum(s.wrapT));
    if (cube) glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glTexParameterf(target, GL_TEXTURE_LOD_BIAS, s.lodBias);
    glTexParameterf(target, GL_TEXTURE_MIN_LOD, s.minLod);
    glTexParameterf(target, GL_TEXTURE_MAX_LOD, s.maxLod);
    // EXT/ARB_texture_filter_anisotropic (the same enum); llvmpipe exposes both.
    glTexParameterf(target, GL_TEXTURE_MAX_ANISOTROPY, s.maxAnisotropy);
}

GLuint UploadTexture(const Texture& tex) {
    const bool cube = tex.kind == TextureKind::Cube;
    const GLenum target = cube ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D;
    GLuint name = 0;
    glGenTextures(1, &name);
    glBindTexture(target, name);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    const bool isFloat = tex.format == raster::TexelFormat::Rgba32F;
    for (int l = 0; l < tex.NumLevels(); ++l) {
        const int w = tex.LevelWidth(l), h = tex.LevelHeight(l);
        const size_t faceBytes = size_t(w) * size_t(h) * size_t(tex.TexelBytes());
        for (int f = 0; f < tex.Faces(); ++f) {
            const GLenum faceTarget = cube ? GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f) : target;
            glTexImage2D(faceTarget, l, isFloat ? GL_RGBA32F : GL_RGBA8, w, h, 0, GL_RGBA,
                         isFloat ? GL_FLOAT : GL_UNSIGNED_BYTE,
                         tex.levels[size_t(l)].data() + size_t(f) * faceBytes);
        }
    }
    SetSamplerParameters(target, tex);
    CheckGl("texture upload");
    return name;
}

// Programs --------------------------------------------------------------------------------------

// A program's shape: unit count and, per unit, whether it samples a cube map.
using ProgramKey = std::tuple<int, bool, bool>;

std::string VertexSource(int numUnits) {
    std::string src = "#version 330 core\nlayout(location=0) in vec4 a_pos;\n";
    for (int u = 0; u < numUnits; ++u)
        src += "layout(location=" + std::to_string(1 + u) + ") in vec3 a_c" + std::to_string(u) +
               ";\nout vec3 v_c" + std::to_string(u) + ";\n";
    src += "layout(location=3) in vec4 a_col;\nout vec4 v_col;\n";
    src += "void main(){ gl_Position=a_pos;";
    for (int u = 0; u < numUnits; ++u)
        src += " v_c" + std::to_string(u) + "=a_c" + std::to_string(u) + ";";
    return src + " v_col=a_col; }\n";
}

std::string FragmentSource(const ProgramKey& key) {
    const int numUnits = std::get<0>(key);
    const bool cube[2] = {std::get<1>(key), std::get<2>(key)};
    std::string src = "#version 330 core\n";
    std::string expr;
    for (int u = 0; u < numUnits; ++u) {
        const std::string n = std::to_string(u);
        src += std::string("uniform ") + (cube[u] ? "samplerCube" : "sampler2D") + " u" + n +
               ";\nin vec3 v_c" + n + ";\n";
        expr += "texture(u" + n + ", v_c" + n + (cube[u] ? "" : ".xy") + ") * ";
    }
    src += "in vec4 v_col;\nlayout(location=0) out vec4 o_col;\n";
    return src + "void main(){ o_col = " + expr + "v_col; }\n";
}

GLuint CompileShader(GLenum type, const std::string& source) {
    const GLuint shader = glCreateShader(type);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw GlError(std::string("shader compilation failed: ") + log);
    }
    return shader;
}

GLuint BuildProgram(const ProgramKey& key) {
    const GLuint vs = CompileShader(GL_VERTEX_SHADER, VertexSource(std::get<0>(key)));
    const GLuint fs = CompileShader(GL_FRAGMENT_SHADER, FragmentSource(key));
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) throw GlError("program link failed");
    glUseProgram(program);
    for (int u = 0; u < std::get<0>(key); ++u) {
        const char name[3] = {'u', static_cast<char>('0' + u), '\0'};
        glUniform1i(glGetUniformLocation(program, name), u);
    }
    CheckGl("program setup");
    return program;
}

// Passes -----------------------------------------------------------------------------------------

// GL objects and state of one pass, prepared before the timed loop.
struct PassDraw {
    GLuint program = 0, vertexArray = 0;
    GLenum seamless = 0;  // 0: no cube map sampled; else GL_TRUE / GL_FALSE
};

std::vector<float> InterleavedFloats(const Pass& pass) {
    std::vector<float> floats;
    for (const raster::Vertex& v : pass.vertices) {
        for (int c = 0; c < 4; ++c) floats.push_back(v.pos[c]);
        for (int u = 0; u < pass.numUnits; ++u)
            for (int c = 0; c < 3; ++c) floats.push_back(v.coord[size_t(u)][c]);
        for (int c = 0; c < 4; ++c) floats.push_back(v.color[c]);
    }
    return floats;
}

GLuint MakeBuffer(GLenum target, const void* data, size_t bytes, GlObjects* objects) {
    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    objects->buffers.push_back(buffer);
    glBindBuffer(target, buffer);
    glBufferData(target, GLsizeiptr(bytes), data, GL_STATIC_DRAW);
    return buffer;
}

void SetupVertexArray(const Pass& pass, GlObjects* objects) {
    const std::vector<float> floats = InterleavedFloats(pass);
    MakeBuffer(GL_ARRAY_BUFFER, floats.data(), floats.size() * sizeof(float), objects);
    const GLsizei stride = GLsizei((8 + 3 * pass.numUnits) * int(sizeof(float)));
    auto attrib = [&](GLuint location, GLint size, int offsetFloats) {
        glEnableVertexAttribArray(location);
        glVertexAttribPointer(location, size, GL_FLOAT, GL_FALSE, stride,
                              reinterpret_cast<const void*>(size_t(offsetFloats) * sizeof(float)));
    };
    attrib(0, 4, 0);
    for (int u = 0; u < pass.numUnits; ++u) attrib(GLuint(1 + u), 3, 4 + 3 * u);
    attrib(3, 4, 4 + 3 * pass.numUnits);
    // Always an index buffer (0..n-1 for non-indexed passes): Mesa 22.3.6 llvmpipe's
    // glDrawArrays path analyses triangle lists for rectangles and can drop a whole draw when a
    // triangle is degenerate in y; indexed draws do not take that path.
    std::vector<uint32_t> sequential;
    if (pass.indices.empty()) {
        sequential.resize(pass.vertices.size());
        for (size_t i = 0; i < sequential.size(); ++i) sequential[i] = uint32_t(i);
    }
    const std::vector<uint32_t>& indices = pass.indices.empty() ? sequential : pass.indices;
    MakeBuffer(GL_ELEMENT_ARRAY_BUFFER, indices.data(), indices.size() * sizeof(uint32_t), objects);
}

PassDraw PreparePass(const Frame& frame, const Pass& pass, std::map<ProgramKey, GLuint>* programs,
                     GlObjects* objects) {
    PassDraw draw;
    bool cube[2] = {false, false};
    for (int u = 0; u < pass.numUnits; ++u) {
        const Texture& tex = frame.textures[size_t(pass.texture[size_t(u)])];
        cube[u] = tex.kind == TextureKind::Cube;
        if (cube[u]) draw.seamless = tex.sampler.seamless ? GL_TRUE : GL_FALSE;
    }
    const ProgramKey key{pass.numUnits, cube[0], cube[1]};
    if (!programs->count(key)) {
        (*programs)[key] = BuildProgram(key);
        objects->programs.push_back((*programs)[key]);
    }
    draw.program = (*programs)[key];
    glGenVertexArrays(1, &draw.vertexArray);
    objects->vertexArrays.push_back(draw.vertexArray);
    glBindVertexArray(draw.vertexArray);
    SetupVertexArray(pass, objects);
    CheckGl("vertex setup");
    return draw;
}

void SetBlend(const raster::BlendState& b) {
    if (!b.enabled) {
        glDisable(GL_BLEND);
        return;
    }
    static constexpr GLenum kFactors[] = {GL_ZERO,
                                          GL_ONE,
                                          GL_SRC_COLOR,
                                          GL_ONE_MINUS_SRC_COLOR,
                                          GL_DST_COLOR,
                                          GL_ONE_MINUS_DST_COLOR,
                                          GL_SRC_ALPHA,
                                          GL_ONE_MINUS_SRC_ALPHA,
                                          GL_DST_ALPHA,
                                          GL_ONE_MINUS_DST_ALPHA,
                                          GL_SRC_ALPHA_SATURATE};
    static constexpr GLenum kEquations[] = {GL_FUNC_ADD, GL_FUNC_SUBTRACT, GL_FUNC_REVERSE_SUBTRACT,
                                            GL_MIN, GL_MAX};
    glEnable(GL_BLEND);
    glBlendFuncSeparate(kFactors[int(b.srcRgb)], kFactors[int(b.dstRgb)], kFactors[int(b.srcAlpha)],
                        kFactors[int(b.dstAlpha)]);
    glBlendEquationSeparate(kEquations[int(b.eqRgb)], kEquations[int(b.eqAlpha)]);
}

// GL_DEPTH_TEST, glDepthFunc and glDepthMask of a pass (absent: the test disabled).
void SetDepthTest(const std::optional<raster::DepthTest>& test) {
    if (!test) {
        glDisable(GL_DEPTH_TEST);
        return;
    }
    static constexpr GLenum kFuncs[] = {GL_NEVER,   GL_LESS,     GL_EQUAL,  GL_LEQUAL,
                                        GL_GREATER, GL_NOTEQUAL, GL_GEQUAL, GL_ALWAYS};
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(kFuncs[int(test->func)]);
    glDepthMask(test->write ? GL_TRUE : GL_FALSE);
}

void DrawPass(const Frame& frame, const Pass& pass, const PassDraw& draw,
              const std::vector<GLuint>& textures) {
    if (draw.seamless == GL_TRUE) glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    if (draw.seamless == GL_FALSE) glDisable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    for (int u = 0; u < pass.numUnits; ++u) {
        const size_t t = size_t(pass.texture[size_t(u)]);
        glActiveTexture(GLenum(GL_TEXTURE0 + u));
        glBindTexture(
            frame.textures[t].kind == TextureKind::Cube ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D,
            textures[t]);
    }
    SetBlend(pass.blend);
    SetDepthTest(pass.depthTest);
    glUseProgram(draw.program);
    glBindVertexArray(draw.vertexArray);
    const size_t count = pass.indices.empty() ? pass.vertices.size() : pass.indices.size();
    glDrawElements(GL_TRIANGLES, GLsizei(count - count % 3), GL_UNSIGNED_INT, nullptr);
}

// Framebuffer ---------------------------------------------------------------------------------

void SetupFramebuffer(const Frame& frame, GlObjects* objects) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    if (frame.width > maxSize || frame.height > maxSize)
        throw GlError("framebuffer larger than GL_MAX_RENDERBUFFER_SIZE " +
                      std::to_string(maxSize));
    glGenRenderbuffers(1, &objects->renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, objects->renderbuffer);
    const bool isFloat = frame.colorFormat == raster::ColorFormat::Rgba32F;
    glRenderbufferStorage(GL_RENDERBUFFER, isFloat ? GL_RGBA32F : GL_RGBA8, frame.width,
                          frame.height);
    glGenFramebuffers(1, &objects->framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, objects->framebuffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              objects->renderbuffer);
    if (frame.depth) {
        static constexpr GLenum kFormats[] = {GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT24,
                                              GL_DEPTH_COMPONENT32F};
        glGenRenderbuffers(1, &objects->depthRenderbuffer);
        glBindRenderbuffer(GL_RENDERBUFFER, objects->depthRenderbuffer);
        glRenderbufferStorage(GL_RENDERBUFFER, kFormats[int(frame.depth->format)], frame.width,
                              frame.height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                  objects->depthRenderbuffer);
    }
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw GlError(
            std::string(isFloat ? "RGBA32F" : "RGBA8") +
            (frame.depth ? " + depth framebuffer incomplete" : " framebuffer incomplete"));
    // Fixed state of gl_ref_case/1.
    glViewport(0, 0, frame.width, frame.height);
    glDepthRange(0.0, 1.0);
    for (GLenum cap : {GL_DEPTH_TEST, GL_STENCIL_TEST, GL_SCISSOR_TEST, GL_CULL_FACE, GL_DITHER,
                       GL_FRAMEBUFFER_SRGB, GL_MULTISAMPLE})
        glDisable(cap);
    // Core profile: fragment colours are clamped for fixed-point buffers only (GL_FIXED_ONLY).
    glClampColor(GL_CLAMP_READ_COLOR, GL_FALSE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (frame.depthClamp)
        glEnable(GL_DEPTH_CLAMP);
    else
        glDisable(GL_DEPTH_CLAMP);
    CheckGl("framebuffer setup");
}

// The colour buffer's RGBA values of type T (GL_UNSIGNED_BYTE: uint8_t; GL_FLOAT: float),
// rows top-down.
template <class T>
std::vector<T> ReadColourTopDown(const Frame& frame, GLenum type) {
    const size_t row = size_t(frame.width) * 4;
    std::vector<T> bottomUp(row * size_t(frame.height)), topDown(bottomUp.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, frame.width, frame.height, GL_RGBA, type, bottomUp.data());
    CheckGl("glReadPixels");
    for (size_t y = 0; y < size_t(frame.height); ++y)
        std::copy_n(bottomUp.data() + (size_t(frame.height) - 1 - y) * row, row,
                    topDown.data() + y * row);
    return topDown;
}

// The depth buffer, rows top-down, as raster/depth.h stores it: unorm formats read as
// GL_UNSIGNED_INT (Mesa replicates the bits: z16 << 16 | z16, z24 << 8 | z24 >> 16), Z32F as
// GL_FLOAT (the stored floats, copied).
std::vector<uint32_t> ReadDepthTopDown(const Frame& frame) {
    const size_t w = size_t(frame.width), h = size_t(frame.height);
    std::vector<uint32_t> bottomUp(w * h), depth(w * h);
    const bool isFloat = frame.depth->format == raster::DepthFormat::Z32F;
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, frame.width, frame.height, GL_DEPTH_COMPONENT,
                 isFloat ? GL_FLOAT : GL_UNSIGNED_INT, bottomUp.data());
    CheckGl("glReadPixels(GL_DEPTH_COMPONENT)");
    const int shift = isFloat ? 0 : (frame.depth->format == raster::DepthFormat::Z16 ? 16 : 8);
    for (size_t y = 0; y < h; ++y)
        for (size_t x = 0; x < w; ++x) depth[y * w + x] = bottomUp[(h - 1 - y) * w + x] >> shift;
    return depth;
}

void DrawFrame(const Frame& frame, const std::vector<PassDraw>& draws,
               const std::vector<GLuint>& textures) {
    glClearColor(float(frame.clear[0]) / 255.0f, float(frame.clear[1]) / 255.0f,
                 float(frame.clear[2]) / 255.0f, float(frame.clear[3]) / 255.0f);
    GLbitfield buffers = GL_COLOR_BUFFER_BIT;
    if (frame.depth) {
        glDepthMask(GL_TRUE);  // glClear leaves the depth buffer alone under glDepthMask(FALSE)
        glClearDepth(double(frame.depth->clear));
        buffers |= GL_DEPTH_BUFFER_BIT;
    }
    glClear(buffers);
    for (size_t p = 0; p < frame.passes.size(); ++p)
        if (frame.passes[p].NumTriangles() > 0)
            DrawPass(frame, frame.passes[p], draws[p], textures);
}

}  // namespace

std::optional<std::string> GlAvailable() {
    return EnsureGlContext();
}

std::string GlRendererString() {
    RequireContext();
    auto text = [](GLenum name) {
        const GLubyte* s = glGetString(name);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    return text(GL_RENDERER) + " | " + text(GL_VERSION);
}

raster::Image8 RenderWithGl(const Frame& frame, int repeat, std::vector<double>* frameMs,
                            std::vector<uint32_t>* depth, raster::ImageF* floatPixels) {
    RequireContext();
    GlObjects objects;
    // Step 1: untimed setup — framebuffer, textures, programs, vertex arrays.
    SetupFramebuffer(frame, &objects);
    for (const Texture& tex : frame.textures) objects.textures.push_back(UploadTexture(tex));
    std::map<ProgramKey, GLuint> programs;
    std::vector<PassDraw> draws;
    for (const Pass& pass : frame.passes)
        draws.push_back(PreparePass(frame, pass, &programs, &objects));
    // Step 2: timed repeats, each a whole frame between two glFinish calls.
    for (int r = 0; r < std::max(1, repeat); ++r) {
        glFinish();
        const auto start = std::chrono::steady_clock::now();
        DrawFrame(frame, draws, objects.textures);
        glFinish();
        const std::chrono::duration<double, std::milli> elapsed =
            std::chrono::steady_clock::now() - start;
        if (frameMs) frameMs->push_back(elapsed.count());
    }
    CheckGl("draw");
    // Step 3: read back.
    if (depth) *depth = frame.depth ? ReadDepthTopDown(frame) : std::vector<uint32_t>{};
    if (floatPixels)
        *floatPixels = frame.colorFormat == raster::ColorFormat::Rgba32F
                           ? raster::ImageF{frame.width, frame.height,
                                            ReadColourTopDown<float>(frame, GL_FLOAT)}
                           : raster::ImageF{};
    return {frame.width, frame.height, ReadColourTopDown<uint8_t>(frame, GL_UNSIGNED_BYTE)};
}

}  // namespace pem::conformance
