#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/context.h"
#include "render/png.h"
#include "render/shaders.h"

namespace render {

namespace {

// One glyph instance of the text program.
struct GlyphInstance {
  rc::Vec2 anchor;
  float x0, y0, x1, y1;
  float u0, v0, u1, v1;
  Color color;
  float scale;
};
static_assert(sizeof(GlyphInstance) == 48);

GLuint compile(const GlApi& gl, GLenum type, const char* source, const char* name) {
  GLuint shader = gl.CreateShader(type);
  gl.ShaderSource(shader, 1, &source, nullptr);
  gl.CompileShader(shader);
  GLint ok = GL_FALSE;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    gl.GetShaderInfoLog(shader, sizeof log, nullptr, log);
    gl.DeleteShader(shader);
    throw std::runtime_error(std::string("render: shader ") + name + " does not compile: " + log);
  }
  return shader;
}

GLuint link(const GlApi& gl, const char* vertex, const char* fragment, const char* name) {
  GLuint vs = compile(gl, GL_VERTEX_SHADER, vertex, name);
  GLuint fs = compile(gl, GL_FRAGMENT_SHADER, fragment, name);
  GLuint program = gl.CreateProgram();
  gl.AttachShader(program, vs);
  gl.AttachShader(program, fs);
  gl.LinkProgram(program);
  gl.DeleteShader(vs);
  gl.DeleteShader(fs);
  GLint ok = GL_FALSE;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    gl.GetProgramInfoLog(program, sizeof log, nullptr, log);
    gl.DeleteProgram(program);
    throw std::runtime_error(std::string("render: program ") + name + " does not link: " + log);
  }
  return program;
}

const void* offset(std::size_t bytes) {
  return reinterpret_cast<const void*>(bytes);
}

void checkGl(const GlApi& gl, const char* where) {
  GLenum error = gl.GetError();
  if (error != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", error);
    throw std::runtime_error(std::string("render: OpenGL error ") + code + " in " + where);
  }
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

struct Renderer::Gpu {
  GLuint shapeProgram = 0, textProgram = 0, spriteProgram = 0;
  GLuint shapeVao = 0, textVao = 0, spriteVao = 0;
  GLuint shapeBuffer = 0, pointBuffer = 0, glyphBuffer = 0, spriteBuffer = 0;
  GLuint atlas = 0;
  GLint maxTextureSize = 0;
  struct Texture {
    GLuint name = 0;
    int width = 0, height = 0;
  };
  std::vector<Texture> sprites;                 // SpriteId value - 1
  std::map<std::string, SpriteId> spritePaths;  // absolute, normalised path of each loaded PNG
  GLuint framebuffer = 0, colorBuffer = 0;
  int width = 0, height = 0;
  GLint maxSize = 0;
  // Uniform locations.
  GLint shapeToPixel = -1, shapeViewport = -1, shapePixelsPerUnit = -1;
  GLint textToPixel = -1, textViewport = -1, textAtlas = -1, textOnEdge = -1, textDistance = -1;
  GLint spriteToPixel = -1, spriteViewport = -1, spritePixelsPerUnit = -1, spriteImage = -1;
  // Scratch reused across frames.
  std::vector<Font::Quad> quads;
  std::vector<GlyphInstance> glyphs;
};

Renderer::Renderer(const RendererOptions& options)
    : context_(std::make_unique<GlContext>()),
      font_(
          std::make_unique<Font>(options.fontPath.empty() ? defaultFontPath() : options.fontPath)),
      gpu_(std::make_unique<Gpu>()) {
  const GlApi& gl = context_->gl();
  Gpu& g = *gpu_;
  g.shapeProgram = link(gl, shaders::kShapeVertex, shaders::kShapeFragment, "shapes");
  g.textProgram = link(gl, shaders::kTextVertex, shaders::kTextFragment, "text");
  g.shapeToPixel = gl.GetUniformLocation(g.shapeProgram, "uToPixel");
  g.shapeViewport = gl.GetUniformLocation(g.shapeProgram, "uViewport");
  g.shapePixelsPerUnit = gl.GetUniformLocation(g.shapeProgram, "uPixelsPerUnit");
  g.textToPixel = gl.GetUniformLocation(g.textProgram, "uToPixel");
  g.textViewport = gl.GetUniformLocation(g.textProgram, "uViewport");
  g.textAtlas = gl.GetUniformLocation(g.textProgram, "uAtlas");
  g.textOnEdge = gl.GetUniformLocation(g.textProgram, "uOnEdge");
  g.textDistance = gl.GetUniformLocation(g.textProgram, "uDistanceScale");
  g.spriteProgram = link(gl, shaders::kSpriteVertex, shaders::kSpriteFragment, "sprites");
  g.spriteToPixel = gl.GetUniformLocation(g.spriteProgram, "uToPixel");
  g.spriteViewport = gl.GetUniformLocation(g.spriteProgram, "uViewport");
  g.spritePixelsPerUnit = gl.GetUniformLocation(g.spriteProgram, "uPixelsPerUnit");
  g.spriteImage = gl.GetUniformLocation(g.spriteProgram, "uImage");
  gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &g.maxSize);
  gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &g.maxTextureSize);

  GLuint buffers[4];
  gl.GenBuffers(4, buffers);
  g.shapeBuffer = buffers[0];
  g.pointBuffer = buffers[1];
  g.glyphBuffer = buffers[2];
  g.spriteBuffer = buffers[3];

  // Shapes: every attribute advances once per instance; the quad's corner is gl_VertexID.
  gl.GenVertexArrays(1, &g.shapeVao);
  gl.BindVertexArray(g.shapeVao);
  gl.BindBuffer(GL_ARRAY_BUFFER, g.shapeBuffer);
  constexpr GLsizei kShapeStride = sizeof(Shape);
  gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, kShapeStride, offset(offsetof(Shape, a)));
  gl.VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, kShapeStride, offset(offsetof(Shape, b)));
  gl.VertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, kShapeStride, offset(offsetof(Shape, radius)));
  gl.VertexAttribPointer(3, 4, GL_UNSIGNED_BYTE, GL_TRUE, kShapeStride,
                         offset(offsetof(Shape, fill)));
  gl.VertexAttribPointer(4, 4, GL_UNSIGNED_BYTE, GL_TRUE, kShapeStride,
                         offset(offsetof(Shape, stroke)));
  gl.VertexAttribIPointer(5, 3, GL_UNSIGNED_INT, kShapeStride, offset(offsetof(Shape, kind)));
  for (GLuint i = 0; i < 6; ++i) {
    gl.EnableVertexAttribArray(i);
    gl.VertexAttribDivisor(i, 1);
  }

  gl.GenVertexArrays(1, &g.textVao);
  gl.BindVertexArray(g.textVao);
  gl.BindBuffer(GL_ARRAY_BUFFER, g.glyphBuffer);
  constexpr GLsizei kGlyphStride = sizeof(GlyphInstance);
  gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, kGlyphStride,
                         offset(offsetof(GlyphInstance, anchor)));
  gl.VertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, kGlyphStride,
                         offset(offsetof(GlyphInstance, x0)));
  gl.VertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, kGlyphStride,
                         offset(offsetof(GlyphInstance, u0)));
  gl.VertexAttribPointer(3, 4, GL_UNSIGNED_BYTE, GL_TRUE, kGlyphStride,
                         offset(offsetof(GlyphInstance, color)));
  gl.VertexAttribPointer(4, 1, GL_FLOAT, GL_FALSE, kGlyphStride,
                         offset(offsetof(GlyphInstance, scale)));
  for (GLuint i = 0; i < 5; ++i) {
    gl.EnableVertexAttribArray(i);
    gl.VertexAttribDivisor(i, 1);
  }

  gl.GenVertexArrays(1, &g.spriteVao);
  gl.BindVertexArray(g.spriteVao);
  gl.BindBuffer(GL_ARRAY_BUFFER, g.spriteBuffer);
  constexpr GLsizei kSpriteStride = sizeof(Sprite);
  gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, kSpriteStride, offset(offsetof(Sprite, center)));
  gl.VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, kSpriteStride, offset(offsetof(Sprite, size)));
  gl.VertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, kSpriteStride, offset(offsetof(Sprite, angle)));
  gl.VertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, kSpriteStride, offset(offsetof(Sprite, source)));
  gl.VertexAttribPointer(4, 4, GL_UNSIGNED_BYTE, GL_TRUE, kSpriteStride,
                         offset(offsetof(Sprite, tint)));
  for (GLuint i = 0; i < 5; ++i) {
    gl.EnableVertexAttribArray(i);
    gl.VertexAttribDivisor(i, 1);
  }
  gl.BindVertexArray(0);

  // The font atlas, uploaded once: one byte per texel, bilinear so distances interpolate.
  gl.GenTextures(1, &g.atlas);
  gl.BindTexture(GL_TEXTURE_2D, g.atlas);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, font_->atlasWidth(), font_->atlasHeight(), 0, GL_RED,
                GL_UNSIGNED_BYTE, font_->atlas().data());
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  gl.GenFramebuffers(1, &g.framebuffer);
  gl.GenRenderbuffers(1, &g.colorBuffer);
  checkGl(gl, "renderer setup");
}

Renderer::~Renderer() {
  if (!context_ || !gpu_) return;
  try {
    context_->makeCurrent();
  } catch (...) {
    return;  // the context goes with everything in it
  }
  const GlApi& gl = context_->gl();
  Gpu& g = *gpu_;
  gl.DeleteProgram(g.shapeProgram);
  gl.DeleteProgram(g.textProgram);
  gl.DeleteProgram(g.spriteProgram);
  gl.DeleteVertexArrays(1, &g.shapeVao);
  gl.DeleteVertexArrays(1, &g.textVao);
  gl.DeleteVertexArrays(1, &g.spriteVao);
  GLuint buffers[4] = {g.shapeBuffer, g.pointBuffer, g.glyphBuffer, g.spriteBuffer};
  gl.DeleteBuffers(4, buffers);
  gl.DeleteTextures(1, &g.atlas);
  for (const Gpu::Texture& t : g.sprites)
    gl.DeleteTextures(1, &t.name);
  gl.DeleteFramebuffers(1, &g.framebuffer);
  gl.DeleteRenderbuffers(1, &g.colorBuffer);
}

SpriteId Renderer::loadSprite(const std::filesystem::path& path) {
  const std::string key = std::filesystem::absolute(path).lexically_normal().string();
  if (auto found = gpu_->spritePaths.find(key); found != gpu_->spritePaths.end()) {
    return found->second;
  }
  const Image image = readPng(path);  // its errors name the file
  if (image.width > gpu_->maxTextureSize || image.height > gpu_->maxTextureSize) {
    throw std::runtime_error("render: sprite '" + path.string() + "' is " +
                             std::to_string(image.width) + "x" + std::to_string(image.height) +
                             ", larger than the " + std::to_string(gpu_->maxTextureSize) +
                             " pixels a side a texture may have");
  }
  const SpriteId id = addSprite(image);
  gpu_->spritePaths.emplace(key, id);
  return id;
}

SpriteId Renderer::addSprite(const Image& image) {
  Gpu& g = *gpu_;
  if (image.width <= 0 || image.height <= 0 || image.width > g.maxTextureSize ||
      image.height > g.maxTextureSize ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
    throw std::invalid_argument("render: a sprite must be 1 to " +
                                std::to_string(g.maxTextureSize) +
                                " pixels a side with 4 bytes a pixel, got " +
                                std::to_string(image.width) + "x" + std::to_string(image.height));
  }
  // Premultiplied once here: filtering then blends colours weighted by their coverage, and the
  // shader's output is what the blend function (ONE, ONE_MINUS_SRC_ALPHA) expects.
  std::vector<std::uint8_t> texels(image.rgba.size());
  for (std::size_t i = 0; i < texels.size(); i += 4) {
    const unsigned a = image.rgba[i + 3];
    for (std::size_t c = 0; c < 3; ++c)
      texels[i + c] = static_cast<std::uint8_t>((image.rgba[i + c] * a + 127u) / 255u);
    texels[i + 3] = static_cast<std::uint8_t>(a);
  }
  context_->makeCurrent();
  const GlApi& gl = context_->gl();
  Gpu::Texture t{0, image.width, image.height};
  gl.GenTextures(1, &t.name);
  gl.BindTexture(GL_TEXTURE_2D, t.name);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                texels.data());
  // Linear, with mipmaps: sprites are turned and scaled to any size, and a sprite drawn at a
  // fraction of its pixels (a 64-pixel crate 10 pixels wide) would shimmer with nearest texels.
  // Pixel art wanting hard texels can be drawn at whole multiples of its size.
  gl.GenerateMipmap(GL_TEXTURE_2D);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  if (gl.GetError() != GL_NO_ERROR) {
    gl.DeleteTextures(1, &t.name);
    throw std::runtime_error("render: OpenGL error uploading a " + std::to_string(image.width) +
                             "x" + std::to_string(image.height) + " sprite");
  }
  g.sprites.push_back(t);
  return SpriteId{static_cast<std::uint32_t>(g.sprites.size())};
}

Renderer::SpriteSize Renderer::spriteSize(SpriteId id) const {
  if (!id.valid() || id.value > gpu_->sprites.size()) {
    throw std::invalid_argument("render: sprite id " + std::to_string(id.value) +
                                " was not made by this Renderer");
  }
  const Gpu::Texture& t = gpu_->sprites[id.value - 1];
  return {t.width, t.height};
}

Image Renderer::render(const Frame& frame, const Camera& camera) {
  Image image;
  render(frame, camera, image);
  return image;
}

void Renderer::render(const Frame& frame, const Camera& camera, Image& out) {
  const auto start = std::chrono::steady_clock::now();
  Gpu& g = *gpu_;
  if (camera.width <= 0 || camera.height <= 0 || camera.width > g.maxSize ||
      camera.height > g.maxSize) {
    throw std::invalid_argument("render: frame size must be 1 to " + std::to_string(g.maxSize) +
                                " pixels a side, got " + std::to_string(camera.width) + "x" +
                                std::to_string(camera.height));
  }
  if (!(std::isfinite(camera.zoom) && camera.zoom > 0.0f) || !rc::isFinite(camera.center)) {
    throw std::invalid_argument("render: camera zoom must be finite and > 0 and its centre finite");
  }
  // Sprites are checked against the images they name before anything is drawn.
  for (const DrawList* list : {&frame.world, &frame.overlay, &frame.hud}) {
    for (const Sprite& sprite : list->sprites) {
      const SpriteSize size = spriteSize(sprite.image);
      const SpriteRect& r = sprite.source;
      if (r.x + r.width > static_cast<float>(size.width) ||
          r.y + r.height > static_cast<float>(size.height)) {
        char rect[96];
        std::snprintf(rect, sizeof rect, "(%g, %g, %g x %g)", static_cast<double>(r.x),
                      static_cast<double>(r.y), static_cast<double>(r.width),
                      static_cast<double>(r.height));
        throw std::invalid_argument("render: sprite source rectangle " + std::string(rect) +
                                    " goes outside its " + std::to_string(size.width) + "x" +
                                    std::to_string(size.height) + " image");
      }
    }
  }
  context_->makeCurrent();
  const GlApi& gl = context_->gl();
  timing_ = {};

  if (camera.width != g.width || camera.height != g.height) {
    gl.BindRenderbuffer(GL_RENDERBUFFER, g.colorBuffer);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, camera.width, camera.height);
    gl.BindFramebuffer(GL_FRAMEBUFFER, g.framebuffer);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                               g.colorBuffer);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw std::runtime_error("render: cannot make a " + std::to_string(camera.width) + "x" +
                               std::to_string(camera.height) + " framebuffer");
    }
    g.width = camera.width;
    g.height = camera.height;
  }
  gl.BindFramebuffer(GL_FRAMEBUFFER, g.framebuffer);
  gl.Viewport(0, 0, g.width, g.height);
  gl.Disable(GL_DEPTH_TEST);
  gl.Disable(GL_CULL_FACE);
  // Shaders output premultiplied colour.
  gl.Enable(GL_BLEND);
  gl.BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  const Color bg = frame.background;
  gl.ClearColor(static_cast<float>(bg.r) / 255.0f, static_cast<float>(bg.g) / 255.0f,
                static_cast<float>(bg.b) / 255.0f, 1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT);

  const float w = static_cast<float>(g.width);
  const float h = static_cast<float>(g.height);
  const float zoom = camera.zoom;
  // pixel = p * xy + zw (see Camera::worldToPixel), then the HUD's identity.
  const float world[4] = {zoom, -zoom, 0.5f * w - camera.center.x * zoom,
                          0.5f * h + camera.center.y * zoom};
  const float screen[4] = {1.0f, 1.0f, 0.0f, 0.0f};

  auto drawList = [&](const DrawList& list, const float* toPixel, float pixelsPerUnit) {
    // Shapes [first, last) of the list, uploaded once per list.
    auto drawShapes = [&](std::size_t first, std::size_t last) {
      if (first >= last) return;
      gl.UseProgram(g.shapeProgram);
      gl.BindVertexArray(g.shapeVao);
      gl.DrawArraysInstancedBaseInstance(
          GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(last - first), static_cast<GLuint>(first));
      ++timing_.drawCalls;
    };
    if (!list.shapes.empty()) {
      gl.UseProgram(g.shapeProgram);
      gl.Uniform4f(g.shapeToPixel, toPixel[0], toPixel[1], toPixel[2], toPixel[3]);
      gl.Uniform2f(g.shapeViewport, w, h);
      gl.Uniform1f(g.shapePixelsPerUnit, pixelsPerUnit);
      gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, g.pointBuffer);
      // A zero-sized storage buffer is an error; polygons never read the placeholder.
      static const rc::Vec2 kPlaceholder{0.0f, 0.0f};
      const void* points = list.points.empty() ? &kPlaceholder : list.points.data();
      const std::size_t pointBytes =
          list.points.empty() ? sizeof kPlaceholder : list.points.size() * sizeof(rc::Vec2);
      gl.BufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(pointBytes), points,
                    GL_STREAM_DRAW);
      gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, g.pointBuffer);
      gl.BindBuffer(GL_ARRAY_BUFFER, g.shapeBuffer);
      gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(list.shapes.size() * sizeof(Shape)),
                    list.shapes.data(), GL_STREAM_DRAW);
    }
    if (!list.sprites.empty()) {
      gl.UseProgram(g.spriteProgram);
      gl.Uniform4f(g.spriteToPixel, toPixel[0], toPixel[1], toPixel[2], toPixel[3]);
      gl.Uniform2f(g.spriteViewport, w, h);
      gl.Uniform1f(g.spritePixelsPerUnit, pixelsPerUnit);
      gl.Uniform1i(g.spriteImage, 0);
      gl.BindBuffer(GL_ARRAY_BUFFER, g.spriteBuffer);
      gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(list.sprites.size() * sizeof(Sprite)),
                    list.sprites.data(), GL_STREAM_DRAW);
    }
    // In the order added: the shapes before a sprite, then a run of sprites with one image and no
    // shape between them (one call), and so on; the remaining shapes last.
    std::size_t shapesDrawn = 0;
    const std::size_t n = list.sprites.size();
    for (std::size_t i = 0; i < n;) {
      const Sprite& head = list.sprites[i];
      const std::size_t before = std::min<std::size_t>(head.shapesBefore, list.shapes.size());
      if (before > shapesDrawn) {
        drawShapes(shapesDrawn, before);
        shapesDrawn = before;
      }
      std::size_t end = i + 1;
      while (end < n && list.sprites[end].image == head.image &&
             list.sprites[end].shapesBefore == head.shapesBefore) {
        ++end;
      }
      gl.UseProgram(g.spriteProgram);
      gl.ActiveTexture(GL_TEXTURE0);
      gl.BindTexture(GL_TEXTURE_2D, g.sprites[head.image.value - 1].name);
      gl.BindVertexArray(g.spriteVao);
      gl.DrawArraysInstancedBaseInstance(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(end - i),
                                         static_cast<GLuint>(i));
      ++timing_.drawCalls;
      i = end;
    }
    drawShapes(shapesDrawn, list.shapes.size());
    if (!list.texts.empty()) {
      g.glyphs.clear();
      for (const Text& text : list.texts) {
        g.quads.clear();
        font_->layout(text.text, text.sizePixels, text.halign, text.valign, g.quads);
        const float scale = text.sizePixels / font_->bakePixels();
        for (const Font::Quad& q : g.quads) {
          g.glyphs.push_back(
              {text.at, q.x0, q.y0, q.x1, q.y1, q.u0, q.v0, q.u1, q.v1, text.color, scale});
        }
      }
      if (g.glyphs.empty()) return;
      gl.UseProgram(g.textProgram);
      gl.Uniform4f(g.textToPixel, toPixel[0], toPixel[1], toPixel[2], toPixel[3]);
      gl.Uniform2f(g.textViewport, w, h);
      gl.Uniform1i(g.textAtlas, 0);
      gl.Uniform1f(g.textOnEdge, static_cast<float>(Font::kOnEdge) / 255.0f);
      gl.Uniform1f(g.textDistance, Font::kDistanceScale / 255.0f);
      gl.ActiveTexture(GL_TEXTURE0);
      gl.BindTexture(GL_TEXTURE_2D, g.atlas);
      gl.BindBuffer(GL_ARRAY_BUFFER, g.glyphBuffer);
      gl.BufferData(GL_ARRAY_BUFFER,
                    static_cast<GLsizeiptr>(g.glyphs.size() * sizeof(GlyphInstance)),
                    g.glyphs.data(), GL_STREAM_DRAW);
      gl.BindVertexArray(g.textVao);
      gl.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(g.glyphs.size()));
      ++timing_.drawCalls;
    }
  };
  drawList(frame.world, world, zoom);
  if (frame.showOverlay) drawList(frame.overlay, world, zoom);
  drawList(frame.hud, screen, 1.0f);
  gl.BindVertexArray(0);
  gl.Finish();
  checkGl(gl, "drawing a frame");
  timing_.drawSeconds = secondsSince(start);

  // Row 0 of the framebuffer holds the top of the picture (see shaders.h): read it straight.
  const auto readStart = std::chrono::steady_clock::now();
  if (out.width != g.width || out.height != g.height) out = Image(g.width, g.height);
  gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl.ReadPixels(0, 0, g.width, g.height, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
  checkGl(gl, "reading a frame back");
  timing_.readbackSeconds = secondsSince(readStart);
}

}  // namespace render
