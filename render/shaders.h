// GLSL 4.50 sources of the renderer's three programs.
//
// Shapes: one instance per Shape (draw_list.h), drawn as a quad around its bounds (capsules,
// segments and arrows: an oriented quad along the shaft); the fragment
// shader measures the signed distance from the pixel to the shape's edge (in pixels, negative
// inside) and turns it into coverage over a one-pixel ramp, which is the anti-aliasing. Text:
// one instance per glyph, sampling the font's distance-field atlas the same way. Sprites: one
// instance per Sprite, a quad one pixel larger than the sprite all round; its coverage is the
// distance to the sprite's rectangle turned into the same one-pixel ramp, times the texel.
//
// Both map pixel row 0 (the top of the picture) to the framebuffer's first row, so glReadPixels
// returns rows top first and no flip is needed on the CPU.
#pragma once

namespace render::shaders {

inline constexpr const char* kShapeVertex = R"(#version 450 core
layout(location = 0) in vec2 iA;
layout(location = 1) in vec2 iB;
layout(location = 2) in vec4 iSizes;  // radius, radius px, stroke px, head px
layout(location = 3) in vec4 iFill;
layout(location = 4) in vec4 iStroke;
layout(location = 5) in uvec3 iKind;  // kind, first point, point count

uniform vec4 uToPixel;  // pixel = p * xy + zw
uniform vec2 uViewport;
uniform float uPixelsPerUnit;

out vec2 vPos;
flat out vec2 vA;
flat out vec2 vB;
flat out vec4 vSizes;
flat out vec4 vFill;
flat out vec4 vStroke;
flat out uvec3 vKind;

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
  float padPixels = max(iSizes.y, iKind.x == 3u ? 0.5 * iSizes.w : 0.0) + 1.0;
  float pad = iSizes.x + padPixels / uPixelsPerUnit;
  vec2 e = iB - iA;
  float len = length(e);
  if ((iKind.x == 1u || iKind.x == 3u) && len > 0.0) {
    // Capsules, segments and arrows: a quad along the shaft, so that a long slanted line costs
    // the pixels around it, not all those of its bounding box.
    vec2 u = e / len;
    vec2 n = vec2(-u.y, u.x);
    vPos = iA - pad * u + corner.x * (e + 2.0 * pad * u) + (2.0 * corner.y - 1.0) * pad * n;
  } else {
    vec2 lo = min(iA, iB) - vec2(pad);
    vec2 hi = max(iA, iB) + vec2(pad);
    vPos = mix(lo, hi, corner);
  }
  vec2 pixel = vPos * uToPixel.xy + uToPixel.zw;
  gl_Position = vec4(pixel / uViewport * 2.0 - 1.0, 0.0, 1.0);
  vA = iA;
  vB = iB;
  vSizes = iSizes;
  vFill = vec4(iFill.rgb * iFill.a, iFill.a);
  vStroke = vec4(iStroke.rgb * iStroke.a, iStroke.a);
  vKind = iKind;
}
)";

inline constexpr const char* kShapeFragment = R"(#version 450 core
layout(std430, binding = 0) readonly buffer Points { vec2 points[]; };

uniform float uPixelsPerUnit;

in vec2 vPos;
flat in vec2 vA;
flat in vec2 vB;
flat in vec4 vSizes;
flat in vec4 vFill;
flat in vec4 vStroke;
flat in uvec3 vKind;

out vec4 fragColor;

float sdSegment(vec2 p, vec2 a, vec2 b) {
  vec2 e = b - a;
  vec2 w = p - a;
  float t = clamp(dot(w, e) / max(dot(e, e), 1e-30), 0.0, 1.0);
  return length(w - e * t);
}

// Exact signed distance to a counter-clockwise convex polygon.
float sdConvex(vec2 p, uint first, uint count) {
  float dmin = 3.0e38;
  bool inside = true;
  vec2 v0 = points[first + count - 1u];
  for (uint i = 0u; i < count; ++i) {
    vec2 v1 = points[first + i];
    vec2 e = v1 - v0;
    vec2 w = p - v0;
    float t = clamp(dot(w, e) / max(dot(e, e), 1e-30), 0.0, 1.0);
    dmin = min(dmin, length(w - e * t));
    if (e.x * w.y - e.y * w.x < 0.0) inside = false;
    v0 = v1;
  }
  return inside ? -dmin : dmin;
}

float sdTriangle(vec2 p, vec2 a, vec2 b, vec2 c) {
  float d = min(sdSegment(p, a, b), min(sdSegment(p, b, c), sdSegment(p, c, a)));
  vec2 e0 = b - a, e1 = c - b, e2 = a - c;
  float s = sign(e0.x * e2.y - e0.y * e2.x);  // either winding
  bool inside = s * (e0.x * (p - a).y - e0.y * (p - a).x) <= 0.0 &&
                s * (e1.x * (p - b).y - e1.y * (p - b).x) <= 0.0 &&
                s * (e2.x * (p - c).y - e2.y * (p - c).x) <= 0.0;
  return inside ? -d : d;
}

void main() {
  float ppu = uPixelsPerUnit;
  float radiusPixels = vSizes.x * ppu + vSizes.y;
  float d;  // signed distance to the edge in pixels, negative inside
  uint kind = vKind.x;
  if (kind == 0u) {
    d = length(vPos - vA) * ppu - radiusPixels;
  } else if (kind == 1u) {
    d = sdSegment(vPos, vA, vB) * ppu - radiusPixels;
  } else if (kind == 2u) {
    d = sdConvex(vPos, vKind.y, vKind.z) * ppu - radiusPixels;
  } else {
    vec2 shaft = vB - vA;
    float len = length(shaft);
    float head = min(vSizes.w / ppu, len);
    if (head <= 0.0) {
      d = sdSegment(vPos, vA, vB) * ppu - radiusPixels;
    } else {
      vec2 dir = shaft / len;
      vec2 side = vec2(-dir.y, dir.x) * (0.5 * head);
      vec2 base = vB - dir * head;
      float dShaft = sdSegment(vPos, vA, base) * ppu - radiusPixels;
      float dHead = sdTriangle(vPos, vB, base + side, base - side) * ppu;
      d = min(dShaft, dHead);
    }
  }
  // Box-filtered coverage of a one-pixel-wide pixel by the half-plane at distance d.
  float outer = clamp(0.5 - d, 0.0, 1.0);
  float inner = vSizes.z > 0.0 ? clamp(0.5 - (d + vSizes.z), 0.0, 1.0) : 1.0;
  fragColor = mix(vStroke, vFill, inner) * outer;
}
)";

inline constexpr const char* kTextVertex = R"(#version 450 core
layout(location = 0) in vec2 iAnchor;
layout(location = 1) in vec4 iRect;  // pixel offsets from the anchor: x0, y0, x1, y1
layout(location = 2) in vec4 iUv;    // u0, v0, u1, v1
layout(location = 3) in vec4 iColor;
layout(location = 4) in float iScale;  // screen pixels per atlas pixel

uniform vec4 uToPixel;
uniform vec2 uViewport;

out vec2 vUv;
flat out vec4 vColor;
flat out float vScale;

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
  // Whole-pixel anchors keep the same text equally sharp wherever it is placed.
  vec2 anchor = floor(iAnchor * uToPixel.xy + uToPixel.zw + 0.5);
  vec2 pixel = anchor + mix(iRect.xy, iRect.zw, corner);
  gl_Position = vec4(pixel / uViewport * 2.0 - 1.0, 0.0, 1.0);
  vUv = mix(iUv.xy, iUv.zw, corner);
  vColor = vec4(iColor.rgb * iColor.a, iColor.a);
  vScale = iScale;
}
)";

inline constexpr const char* kTextFragment = R"(#version 450 core
uniform sampler2D uAtlas;
uniform float uOnEdge;         // texel value on the outline, 0..1
uniform float uDistanceScale;  // texel value (0..1) per atlas pixel

in vec2 vUv;
flat in vec4 vColor;
flat in float vScale;

out vec4 fragColor;

void main() {
  float d = (texture(uAtlas, vUv).r - uOnEdge) / uDistanceScale * vScale;  // pixels, + inside
  fragColor = vColor * clamp(d + 0.5, 0.0, 1.0);
}
)";

// Texels are premultiplied when the image is uploaded, so bilinear filtering never mixes in the
// colour of a transparent texel (no dark fringe around a cut-out) and the product of texel and
// premultiplied tint is the premultiplied colour the blend function expects.
inline constexpr const char* kSpriteVertex = R"(#version 450 core
layout(location = 0) in vec2 iCenter;
layout(location = 1) in vec2 iSize;
layout(location = 2) in float iAngle;
layout(location = 3) in vec4 iSource;  // x, y, width, height in texels; width 0: the whole image
layout(location = 4) in vec4 iTint;

uniform vec4 uToPixel;
uniform vec2 uViewport;
uniform float uPixelsPerUnit;
uniform sampler2D uImage;

out vec2 vLocal;  // list units from the centre before turning, +y towards the image's top
out vec2 vTexel;  // texel coordinates, not clamped to the source rectangle
flat out vec2 vHalf;
flat out vec4 vSource;
flat out vec4 vTint;

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));  // y 0: the image's top
  vec2 imageSize = vec2(textureSize(uImage, 0));
  vec4 source = iSource.z > 0.0 ? iSource : vec4(0.0, 0.0, imageSize);
  vec2 halfSize = 0.5 * iSize;
  vec2 grown = halfSize + vec2(1.0 / uPixelsPerUnit);  // room for the anti-aliased edge
  vec2 local = vec2(corner.x - 0.5, 0.5 - corner.y) * 2.0 * grown;
  vec2 t = vec2(local.x / iSize.x + 0.5, 0.5 - local.y / iSize.y);
  vTexel = source.xy + t * source.zw;
  // Turn counter-clockwise as seen in the picture, then into the list's space, whose y points up
  // (world: uToPixel.y < 0) or down (HUD).
  float c = cos(iAngle), s = sin(iAngle);
  vec2 turned = vec2(c * local.x - s * local.y, s * local.x + c * local.y);
  vec2 p = iCenter + vec2(turned.x, uToPixel.y < 0.0 ? turned.y : -turned.y);
  vec2 pixel = p * uToPixel.xy + uToPixel.zw;
  gl_Position = vec4(pixel / uViewport * 2.0 - 1.0, 0.0, 1.0);
  vLocal = local;
  vHalf = halfSize;
  vSource = source;
  vTint = vec4(iTint.rgb * iTint.a, iTint.a);
}
)";

inline constexpr const char* kSpriteFragment = R"(#version 450 core
uniform float uPixelsPerUnit;
uniform sampler2D uImage;

in vec2 vLocal;
in vec2 vTexel;
flat in vec2 vHalf;
flat in vec4 vSource;
flat in vec4 vTint;

out vec4 fragColor;

void main() {
  vec2 q = abs(vLocal) - vHalf;
  float d = (length(max(q, 0.0)) + min(max(q.x, q.y), 0.0)) * uPixelsPerUnit;
  float coverage = clamp(0.5 - d, 0.0, 1.0);
  // Stay half a texel inside the source rectangle so filtering never reads its neighbours; the
  // gradients of the unclamped coordinates choose the mipmap level, with no jump at the clamp.
  vec2 imageSize = vec2(textureSize(uImage, 0));
  vec2 texel = clamp(vTexel, vSource.xy + 0.5, vSource.xy + vSource.zw - 0.5);
  vec4 color = textureGrad(uImage, texel / imageSize, dFdx(vTexel) / imageSize,
                           dFdy(vTexel) / imageSize);
  fragColor = color * vTint * coverage;
}
)";

}  // namespace render::shaders
