#pragma once
// 3D-texture slicing of bricks (the paper's renderer), in OpenGL 4.5 core. Each brick is a 3D
// texture of its stored samples (ghosts included); it is drawn as view-aligned slice polygons
// blended back to front with premultiplied alpha into a float framebuffer, and read back as RGBA8
// over the screen rectangle its projection covers.
//
// Empty-space skipping: each brick is cut into blocks of up to `block_cells` cells per axis; a
// block whose samples all map to zero opacity is not drawn, and the brick's rectangle covers only
// the blocks that are. Visible blocks are drawn in back-to-front block order, each with its part
// of the shared slice planes; "over" is associative, so this equals slicing the whole brick (up to
// float rounding) while rasterising no fragment in empty blocks.
#include <array>
#include <vector>

#include "common/brick.h"
#include "common/camera.h"
#include "common/image.h"
#include "common/transfer_function.h"
#include "worker/gl_context.h"

namespace sortlast {

struct RenderedBrick {
  Rect rect;           // empty: nothing to draw (invisible under the transfer function, or off screen)
  ImageRGBA8 pixels;   // rect.w x rect.h
};

// An opaque surface already rendered in the same brick (worker/metaball_renderer.h): its colour
// (RGBA32F, premultiplied) and (t, normal) textures, valid over `rect`. Slices behind it are not
// drawn, and what is drawn is blended over it, so the brick image holds both in the right order.
struct SurfaceLayer {
  unsigned colour_texture = 0;
  unsigned surface_texture = 0;
  Rect rect;
};

class SlicingRenderer {
 public:
  SlicingRenderer(const GlContext& ctx, int width, int height, int block_cells = 64);
  ~SlicingRenderer();
  SlicingRenderer(const SlicingRenderer&) = delete;
  SlicingRenderer& operator=(const SlicingRenderer&) = delete;

  void setTransferFunction(const TransferFunction& tf, int table_size);
  // Uploads a brick's stored samples (x fastest); returns a handle for render(). The samples'
  // min and max are kept so invisible bricks can be skipped.
  int addBrick(const Brick& brick, const GridGeometry& grid, const std::vector<float>& samples);

  // Renders one brick for `cam`; `spacing` is the world distance between slice planes and
  // [near_plane, far_plane] must enclose the whole volume (the same for all bricks of a frame).
  RenderedBrick render(int handle, const Camera& cam, double spacing, double near_plane,
                       double far_plane, const SurfaceLayer* surface = nullptr);

 private:
  struct Block {
    Box3 world;
    float vmin, vmax;
  };
  struct GpuBrick {
    Brick brick;
    std::array<std::vector<double>, 3> block_planes;  // world block boundaries per axis
    std::vector<Block> blocks;                        // x fastest over the block grid
    unsigned texture = 0;
    glm::vec3 tex_scale, tex_offset;  // texture coordinate = world * scale + offset
  };
  bool visible(const Block& b) const;

  const GlApi& gl_;
  int width_, height_, block_cells_;
  unsigned fbo_ = 0, colour_ = 0, program_ = 0, vao_ = 0, vbo_ = 0, tf_texture_ = 0;
  TransferFunction tf_;
  int tf_table_size_ = 0;
  std::vector<GpuBrick> bricks_;
  std::vector<float> readback_;
};

}  // namespace sortlast
