// The rectangles of the view that hold its surfaces, one per band of BAND_TILES rows of tiles of
// TILE_SIZE pixels: one invocation per tile scans its linear depths (0 marks background) and, at the
// first surface pixel, widens its band's rectangle to the tile. The present pass shades those
// rectangles only (fullscreen.vert's PRESENT_BOUNDS, an instance each) and fills the rest of the
// view with the background: llvmpipe shades every pixel a draw covers, the background ones too
// (their early return is a masked branch it runs anyway). Bands, not a quad per tile: llvmpipe
// shades the 4x4 blocks a triangle's edge crosses once for each triangle, and sixteen-pixel quads
// made a view full of surface cost a third more than one triangle over it; one rectangle for the
// whole view left much of the background of builtin:demo inside it.
#include "common.glsl"

#ifndef TILE_SIZE
#define TILE_SIZE 16
#endif
#ifndef BAND_TILES
#define BAND_TILES 4
#endif

layout(local_size_x = 8, local_size_y = 8) in;

uniform highp sampler2D u_linear_depth;

// Per band, in tiles: the first column and row, and one past the last; empty (min >= max) where the
// band has no surface.
struct Bounds {
  uint min_x;
  uint min_y;
  uint max_x;
  uint max_y;
};
layout(std430, binding = 0) buffer CoveredBounds { Bounds band[]; } bounds;

void main() {
  ivec2 size = textureSize(u_linear_depth, 0);
  ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
  ivec2 origin = tile * TILE_SIZE;
  if (origin.x >= size.x || origin.y >= size.y) return;
  ivec2 end = min(origin + TILE_SIZE, size);
  bool covered = false;
  for (int y = origin.y; y < end.y && !covered; ++y)
    for (int x = origin.x; x < end.x; ++x)
      if (texelFetch(u_linear_depth, ivec2(x, y), 0).r > 0.0) {
        covered = true;
        break;
      }
  if (!covered) return;
  int band = tile.y / BAND_TILES;
  atomicMin(bounds.band[band].min_x, uint(tile.x));
  atomicMin(bounds.band[band].min_y, uint(tile.y));
  atomicMax(bounds.band[band].max_x, uint(tile.x) + 1u);
  atomicMax(bounds.band[band].max_y, uint(tile.y) + 1u);
}
