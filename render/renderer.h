// Draws Frames off-screen with OpenGL (OSMesa) and reads them back as images.
//
// One Renderer owns one GL context, its shader programs and the font atlas, all made once in the
// constructor (about 0.1 s with the font bake) and reused for every frame, and the sprite images
// loaded into it (one texture each, uploaded once). A frame costs a few draw calls whatever its
// size: per layer, one instanced call for all shapes, one per sprite image and one for all glyphs
// (see draw_list.h for the order). Use a Renderer from one thread at a time; it makes its context
// current on each call.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "render/camera.h"
#include "render/draw_list.h"
#include "render/font.h"
#include "render/image.h"

namespace render {

class GlContext;

struct RendererOptions {
  std::string fontPath;  // empty: defaultFontPath() ($RICOCHET_FONT, else the shipped font)
};

class Renderer {
 public:
  // Throws std::runtime_error when the GL context, a shader or the font cannot be made.
  explicit Renderer(const RendererOptions& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws `frame` as `camera` sees it into `out` (resized to the camera's width x height, row 0
  // at the top of the picture). Reusing `out` across frames avoids an allocation per frame.
  // Throws std::invalid_argument for a bad camera, std::runtime_error on a GL error.
  void render(const Frame& frame, const Camera& camera, Image& out);
  Image render(const Frame& frame, const Camera& camera);

  struct Timing {
    double drawSeconds = 0;      // upload, draw calls and glFinish
    double readbackSeconds = 0;  // glReadPixels
    int drawCalls = 0;
  };
  // Reads a PNG once into a texture this Renderer owns and returns its id for DrawList::sprite;
  // the same path again returns the same id without reading the file. Throws std::runtime_error
  // naming the file when it is missing, unreadable or not a valid PNG, or too large for GL.
  SpriteId loadSprite(const std::filesystem::path& path);
  // The same from an image in memory (generated art); every call makes a new texture.
  SpriteId addSprite(const Image& image);
  struct SpriteSize {
    int width = 0;
    int height = 0;
  };
  // In pixels of the image; throws std::invalid_argument for an id this Renderer did not make.
  SpriteSize spriteSize(SpriteId id) const;

  // Of the last render() call.
  const Timing& lastTiming() const { return timing_; }

  const Font& font() const { return *font_; }
  const GlContext& context() const { return *context_; }

 private:
  struct Gpu;
  std::unique_ptr<GlContext> context_;
  std::unique_ptr<Font> font_;
  std::unique_ptr<Gpu> gpu_;
  Timing timing_;
};

}  // namespace render
