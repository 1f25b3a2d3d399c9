// One frame, from meshes to pixels:
//
//   shadow           the casting meshes' shadow on the ground in the sun (ground_shadow.hpp)
//   vertex stage     world -> clip space; per-vertex lighting (front and back) for Gouraud
//   primitives       flat: per-face lighting; clip (near, far, guard band); project; facing:
//                    cull or pick the back material; snap and set up (triangle_setup.hpp);
//                    in fixed chunks of triangles, each binned on its own: for every tile, its
//                    triangles whose box touches the tile, in order
//   lines            wireframe: each line binned the same way; drawn as Bresenham's line, or as
//                    Wu's (wu_line.hpp) when the frame is anti-aliased
//   tiles            in parallel, each in a small buffer of its own that stays in cache: sky,
//                    the tile's triangles chunk after chunk (tile_raster.hpp), then copied out,
//                    each pixel the mean of its samples when multisampled (sample_pattern.hpp)
//
// A mesh of more than RenderOptions::batch_triangles is drawn in passes, a batch of chunks at a
// time: primitives, then the tiles that the batch's triangles touch, each loaded as the last
// pass left it (every sample's colour and depth), drawn on and saved again. The setups of one batch are
// held at a time (about 200 bytes a triangle), not the whole mesh's, and each tile still meets
// its triangles in the same order, so the image is the same bit for bit.
//
// Every stage's output is in a fixed order whatever the thread count, and each tile is drawn
// by one thread, so the image is the same bit for bit at any number of threads.
#pragma once

#include <cstdint>
#include <vector>

#include "server/render/bresenham.hpp"
#include "server/render/camera.hpp"
#include "server/render/clipping.hpp"
#include "server/render/framebuffer.hpp"
#include "server/render/mesh.hpp"
#include "server/render/sample_pattern.hpp"
#include "server/render/tile_raster.hpp"
#include "server/render/triangle_setup.hpp"

namespace flagsim::render {

struct RenderOptions {
  ShadingMode mode = ShadingMode::kGouraud;
  int threads = 1;
  int tile_size = 64;             ///< px, square tiles (the stream's tiles too), 8 and up
  bool keep_depth = false;        ///< also copy the depth buffer out (tiles keep it to themselves)
  int batch_triangles = 1 << 15;  ///< triangles set up at once; a bigger mesh is drawn in passes
  Antialiasing antialiasing = Antialiasing::kOff;  ///< samples per pixel; lines are Wu's unless off
};

class Renderer {
 public:
  /// Draws `scene` seen by `camera` into `framebuffer` (resized to the camera's image).
  void Render(const RenderScene& scene, const Camera& camera, const RenderOptions& options,
              Framebuffer* framebuffer);

  /// Triangles set up in the last frame (after culling and clipping), for statistics.
  size_t triangles_drawn() const;

 private:
  void VertexStage(const RenderScene& scene, const Eigen::Matrix4f& clip_from_world, ShadingMode mode,
                   int threads);
  /// One primitive-stage work item: a run of a mesh's triangles.
  struct ChunkWork {
    int mesh, first, end;
  };
  void PrimitiveStage(const RenderScene& scene, const std::vector<ChunkWork>& work, ShadingMode mode,
                      int width, int height, int tile_size, int sample_reach, int threads);
  /// `smooth`: Wu's lines (anti-aliased frames), binned a pixel wider; else Bresenham's.
  void LineStage(const RenderScene& scene, int width, int height, int tile_size, bool smooth);
  /// The tiles' pass over the chunks set up last: the first pass clears every tile to the sky,
  /// a later one draws only on the tiles its triangles touch; all but the last keep the depth.
  void TileStage(const ShadeContext& context, const RenderOptions& options, bool first_pass, bool last_pass,
                 Framebuffer* framebuffer);

  /// One primitive-stage work item's triangles, in order, and for each tile those whose box
  /// touches it.
  struct Chunk {
    std::vector<TriangleSetup> setups;
    std::vector<std::vector<uint32_t>> bins;  ///< per tile: indices into setups, in order
  };
  void BinChunk(int width, int height, int tile_size, Chunk* chunk) const;

  Eigen::Vector3f eye_ = Eigen::Vector3f::Zero();
  std::vector<std::vector<ClipVertex>> vertices_;  ///< per mesh, per vertex
  std::vector<Chunk> chunks_;                      ///< the batch's
  size_t triangles_drawn_ = 0;
  std::vector<LineSetup> lines_;
  FilteredTexture pattern_;         ///< the scene's, filtered, for the tiles
  GroundShadow shadow_;             ///< the scene's casters' on the ground, this frame
  std::vector<uint32_t> sky_rows_;  ///< the sky's colour on each row of the image
  int tiles_x_ = 0, tiles_y_ = 0;
  std::vector<std::vector<uint32_t>> line_bins_;  ///< per tile: indices into lines_
  SampleImage between_passes_;                    ///< the tiles' samples, when drawn in passes
};

}  // namespace flagsim::render
