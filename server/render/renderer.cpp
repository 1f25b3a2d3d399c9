#include "server/render/renderer.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "server/parallel/worker_pool.hpp"
#include "server/render/srgb.hpp"
#include "server/render/wu_line.hpp"

namespace flagsim::render {
namespace {

// ClipVertex channel layout. Gouraud: front D rgb, S rgb | back D rgb, S rgb | u, v.
// Flat and Phong: position xyz, normal xyz | the same again | u, v.
constexpr int kFrontBlock = 0, kBackBlock = 6, kUv = 12;
constexpr int kChunk = 256;         ///< triangles per primitive-stage work item
constexpr int kVertexBlock = 1024;  ///< vertices per vertex-stage work item

void PutShade(const Shade& shade, float* channels) {
  for (int k = 0; k < 3; ++k) {
    channels[k] = shade.diffuse[k];
    channels[3 + k] = shade.specular[k];
  }
}

/// Clip space => window position, depth and 1 / w.
ScreenVertex Project(const ClipVertex& v, int width, int height) {
  ScreenVertex s;
  s.inverse_w = 1.0f / v.clip.w();
  s.x = (v.clip.x() * s.inverse_w + 1.0f) * 0.5f * width;
  s.y = (1.0f - v.clip.y() * s.inverse_w) * 0.5f * height;
  s.z = (v.clip.z() * s.inverse_w + 1.0f) * 0.5f;
  return s;
}

/// The side's six light (or position and normal) channels, then u and v.
void PickChannels(const ClipVertex& v, bool back, ScreenVertex* s) {
  const int block = back ? kBackBlock : kFrontBlock;
  std::copy(v.channels + block, v.channels + block + 6, s->channels);
  s->channels[6] = v.channels[kUv];
  s->channels[7] = v.channels[kUv + 1];
}

/// Flat shading: one lighting value per face, from its normal at its centroid.
void ShadeFace(const RenderScene& scene, const Mesh& mesh, const Eigen::Vector3f& eye, ClipVertex v[3]) {
  const Eigen::Vector3f p[3] = {Eigen::Vector3f(v[0].channels), Eigen::Vector3f(v[1].channels),
                                Eigen::Vector3f(v[2].channels)};
  const Eigen::Vector3f centre = (p[0] + p[1] + p[2]) / 3;
  const Eigen::Vector3f normal = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
  const Shade front = ShadePoint(scene.materials[mesh.front_material], scene.lighting, centre, normal, eye);
  Shade back;
  if (mesh.back_material >= 0)
    back = ShadePoint(scene.materials[mesh.back_material], scene.lighting, centre, -normal, eye);
  for (int i = 0; i < 3; ++i) {
    PutShade(front, v[i].channels + kFrontBlock);
    PutShade(back, v[i].channels + kBackBlock);
  }
}

/// The triangle's area in (u, v) over its area in pixels (u, v: channels 6 and 7), for the
/// pattern's level of detail; 0 for a triangle of no area on screen.
float UvAreaPerPixel(const ScreenVertex s[3]) {
  const float screen = std::abs((s[1].x - s[0].x) * (s[2].y - s[0].y) - (s[2].x - s[0].x) * (s[1].y - s[0].y));
  const float uv = std::abs((s[1].channels[6] - s[0].channels[6]) * (s[2].channels[7] - s[0].channels[7]) -
                            (s[2].channels[6] - s[0].channels[6]) * (s[1].channels[7] - s[0].channels[7]));
  return screen > 0 ? uv / screen : 0;
}

/// Clipped, projected, set up: appends what is visible of one triangle to `out`.
void SetupVisible(const Mesh& mesh, const ClipVertex* a, const ClipVertex* b, const ClipVertex* c, int width,
                  int height, int sample_reach, std::vector<TriangleSetup>* out) {
  ScreenVertex s[3];
  const ClipVertex* v[3] = {a, b, c};
  for (int i = 0; i < 3; ++i) s[i] = Project(*v[i], width, height);
  const bool back = IsBackFacing(s[0], s[1], s[2]);
  if (back && mesh.back_material < 0) return;  // culled
  for (int i = 0; i < 3; ++i) PickChannels(*v[i], back, &s[i]);
  TriangleSetup setup;
  if (!SetupTriangle(s[0], s[1], s[2], width, height, &setup, sample_reach)) return;
  setup.material = back ? mesh.back_material : mesh.front_material;
  setup.uv_area_per_pixel = UvAreaPerPixel(s);
  out->push_back(setup);
}

/// Calls visit(tile) for each tile (tiles_x across, tile_size px square) that the pixel box
/// [x0, x1] x [y0, y1], clamped to the width x height image, touches.
template <class Visit>
void ForTilesOfBox(int x0, int y0, int x1, int y1, int width, int height, int tile_size, int tiles_x,
                   Visit visit) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, width - 1);
  y1 = std::min(y1, height - 1);
  if (x0 > x1 || y0 > y1) return;
  for (int ty = y0 / tile_size; ty <= y1 / tile_size; ++ty) {
    for (int tx = x0 / tile_size; tx <= x1 / tile_size; ++tx) visit(ty * tiles_x + tx);
  }
}

}  // namespace

size_t Renderer::triangles_drawn() const { return triangles_drawn_; }

void Renderer::Render(const RenderScene& scene, const Camera& camera, const RenderOptions& options_in,
                      Framebuffer* framebuffer) {
  RenderOptions options = options_in;
  options.tile_size = std::max(options.tile_size, 8);
  if (framebuffer->width != camera.width || framebuffer->height != camera.height) {
    framebuffer->Resize(camera.width, camera.height);
  }
  eye_ = camera.EyeInWorld().cast<float>();
  const Eigen::Matrix4f clip_from_world = (camera.Projection() * camera.View()).cast<float>();
  tiles_x_ = (camera.width + options.tile_size - 1) / options.tile_size;
  tiles_y_ = (camera.height + options.tile_size - 1) / options.tile_size;
  line_bins_.resize(size_t(tiles_x_) * tiles_y_);
  for (std::vector<uint32_t>& bin : line_bins_) bin.clear();
  VertexStage(scene, clip_from_world, options.mode, options.threads);
  pattern_.Assign(scene.pattern);
  shadow_.Cast(scene);
  SkyRows(scene, camera.height, &sky_rows_);
  ShadeContext context;
  context.scene = &scene;
  context.pattern = &pattern_;
  context.mode = options.mode;
  context.eye = eye_;
  context.samples = PatternOf(options.antialiasing);
  context.shadow = &shadow_;
  std::vector<ChunkWork> work;
  if (options.mode == ShadingMode::kWireframe) {
    LineStage(scene, camera.width, camera.height, options.tile_size, options.antialiasing != Antialiasing::kOff);
  } else {
    lines_.clear();
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
      const int count = static_cast<int>(scene.meshes[m].triangles.size());
      for (int first = 0; first < count; first += kChunk)
        work.push_back({int(m), first, std::min(count, first + kChunk)});
    }
  }
  // Batches of chunks; one pass with none for lines alone, or for an empty scene.
  const size_t per_batch = size_t(std::max(1, options.batch_triangles / kChunk));
  triangles_drawn_ = 0;
  for (size_t first = 0;; first += per_batch) {
    const size_t end = std::min(work.size(), first + per_batch);
    const std::vector<ChunkWork> batch(work.begin() + first, work.begin() + end);
    PrimitiveStage(scene, batch, options.mode, camera.width, camera.height, options.tile_size,
                   context.samples.reach, options.threads);
    TileStage(context, options, first == 0, end == work.size(), framebuffer);
    if (end == work.size()) break;
  }
}

// (world position, normal, uv) => (clip position, lighting or position/normal, uv)
void Renderer::VertexStage(const RenderScene& scene, const Eigen::Matrix4f& clip_from_world, ShadingMode mode,
                           int threads) {
  vertices_.resize(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    std::vector<ClipVertex>& out = vertices_[m];
    out.resize(mesh.positions.size());
    const int n = static_cast<int>(mesh.positions.size());
    const auto transform = [&](int i) {
      const Eigen::Vector3f& p = mesh.positions[i];
      const Eigen::Vector3f& normal = mesh.normals[i];
      ClipVertex& v = out[i];
      v.clip = clip_from_world * p.homogeneous();
      v.channels[kUv] = mesh.uvs[i][0];
      v.channels[kUv + 1] = mesh.uvs[i][1];
      if (mode == ShadingMode::kGouraud) {
        PutShade(ShadePoint(scene.materials[mesh.front_material], scene.lighting, p, normal, eye_),
                 v.channels + kFrontBlock);
        const Shade back = mesh.back_material >= 0 ? ShadePoint(scene.materials[mesh.back_material],
                                                                scene.lighting, p, -normal, eye_)
                                                   : Shade{};
        PutShade(back, v.channels + kBackBlock);
      } else {
        for (const int block : {kFrontBlock, kBackBlock}) {
          for (int k = 0; k < 3; ++k) {
            v.channels[block + k] = p[k];
            v.channels[block + 3 + k] = normal[k];
          }
        }
      }
    };
    const int blocks = (n + kVertexBlock - 1) / kVertexBlock;
    ParallelFor(blocks, threads, [&](int block) {
      for (int i = block * kVertexBlock; i < std::min(n, (block + 1) * kVertexBlock); ++i) transform(i);
    });
  }
}

// The batch's chunks of triangles (the same chunks at any thread count), each binned to the tiles.
void Renderer::PrimitiveStage(const RenderScene& scene, const std::vector<ChunkWork>& work, ShadingMode mode,
                              int width, int height, int tile_size, int sample_reach, int threads) {
  chunks_.resize(work.size());
  const int items = static_cast<int>(work.size());
  ParallelFor(items, threads, [&](int w) {
    const Mesh& mesh = scene.meshes[work[w].mesh];
    const std::vector<ClipVertex>& vertices = vertices_[work[w].mesh];
    std::vector<TriangleSetup>& out = chunks_[w].setups;
    out.clear();
    std::vector<ClipVertex> clipped;
    for (int t = work[w].first; t < work[w].end; ++t) {
      ClipVertex v[3] = {vertices[mesh.triangles[t][0]], vertices[mesh.triangles[t][1]],
                         vertices[mesh.triangles[t][2]]};
      if (mode == ShadingMode::kFlat) ShadeFace(scene, mesh, eye_, v);
      switch (ClassifyTriangle(v[0], v[1], v[2])) {
        case ClipTest::kOutside:
          break;
        case ClipTest::kInside:
          SetupVisible(mesh, &v[0], &v[1], &v[2], width, height, sample_reach, &out);
          break;
        case ClipTest::kCrossing:
          clipped.clear();
          ClipTriangle(v[0], v[1], v[2], &clipped);
          for (size_t i = 0; i + 2 < clipped.size(); i += 3) {
            SetupVisible(mesh, &clipped[i], &clipped[i + 1], &clipped[i + 2], width, height, sample_reach, &out);
          }
          break;
      }
    }
    BinChunk(width, height, tile_size, &chunks_[w]);
  });
  for (const Chunk& chunk : chunks_) triangles_drawn_ += chunk.setups.size();
}

void Renderer::BinChunk(int width, int height, int tile_size, Chunk* chunk) const {
  chunk->bins.resize(size_t(tiles_x_) * tiles_y_);
  for (std::vector<uint32_t>& bin : chunk->bins) bin.clear();
  for (uint32_t i = 0; i < chunk->setups.size(); ++i) {
    const TriangleSetup& t = chunk->setups[i];
    ForTilesOfBox(t.min_x, t.min_y, t.max_x, t.max_y, width, height, tile_size, tiles_x_,
                  [&](int tile) { chunk->bins[tile].push_back(i); });
  }
}

// Mesh edges, clipped and projected to pixel endpoints, coloured by their material, and binned.
void Renderer::LineStage(const RenderScene& scene, int width, int height, int tile_size, bool smooth) {
  lines_.clear();
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const Material& material = scene.materials[mesh.front_material];
    for (const auto& [ia, ib] : mesh.edges) {
      Eigen::Vector4f a = vertices_[m][ia].clip, b = vertices_[m][ib].clip;
      if (!ClipLine(&a, &b)) continue;
      Eigen::Vector3f colour = material.colour;  // linear light, encoded below
      if (material.patterned) {
        const uint8_t* texel = scene.pattern.Sample(mesh.uvs[ia][0], mesh.uvs[ia][1]);
        for (int k = 0; k < 3; ++k) colour[k] *= SrgbToLinear(texel[k] / 255.0f);
      }
      LineSetup line;
      const auto to_pixel = [&](const Eigen::Vector4f& v, float* fx, float* fy, int* x, int* y, float* z) {
        *fx = (v.x() / v.w() + 1.0f) * 0.5f * width;
        *fy = (1.0f - v.y() / v.w()) * 0.5f * height;
        *x = static_cast<int>(std::floor(*fx));
        *y = static_cast<int>(std::floor(*fy));
        *z = (v.z() / v.w() + 1.0f) * 0.5f;
      };
      to_pixel(a, &line.fx0, &line.fy0, &line.x0, &line.y0, &line.z0);
      to_pixel(b, &line.fx1, &line.fy1, &line.x1, &line.y1, &line.z1);
      for (int k = 0; k < 3; ++k) line.rgb[k] = static_cast<uint8_t>(EncodeSrgb(colour[k]));
      lines_.push_back(line);
    }
  }
  // Wu's line may touch the pixel next to its endpoints' across the major axis.
  const int margin = smooth ? 1 : 0;
  for (uint32_t i = 0; i < lines_.size(); ++i) {
    const LineSetup& l = lines_[i];
    ForTilesOfBox(std::min(l.x0, l.x1) - margin, std::min(l.y0, l.y1) - margin, std::max(l.x0, l.x1) + margin,
                  std::max(l.y0, l.y1) + margin, width, height, tile_size, tiles_x_,
                  [&](int tile) { line_bins_[tile].push_back(i); });
  }
}

void Renderer::TileStage(const ShadeContext& context, const RenderOptions& options, bool first_pass,
                         bool last_pass, Framebuffer* framebuffer) {
  const int tiles = tiles_x_ * tiles_y_, size = options.tile_size;
  const auto untouched = [this](int tile) {
    return std::all_of(chunks_.begin(), chunks_.end(),
                       [tile](const Chunk& chunk) { return chunk.bins[tile].empty(); });
  };
  const int samples = context.samples.count;
  if (!last_pass || !first_pass) between_passes_.Resize(framebuffer->width, framebuffer->height, samples);
  std::vector<TileBuffer> buffers;  // one per thread
  for (int k = 0; k < std::max(1, options.threads); ++k) buffers.emplace_back(size, samples);
  ParallelForEachParticipant(tiles, options.threads, [&](int index, int participant) {
    const bool drawn_on = first_pass || !untouched(index);
    if (!drawn_on && !last_pass) return;  // its samples wait as they are
    TileRect rect;
    rect.x0 = (index % tiles_x_) * size;
    rect.y0 = (index / tiles_x_) * size;
    rect.x1 = std::min(rect.x0 + size, framebuffer->width);
    rect.y1 = std::min(rect.y0 + size, framebuffer->height);
    const TileTarget target = buffers[participant].Target(rect);
    if (first_pass) {
      ClearTile(sky_rows_.data(), target);
    } else {
      LoadTile(between_passes_, target);
    }
    if (drawn_on) {
      for (const Chunk& chunk : chunks_) {
        for (const uint32_t i : chunk.bins[index]) RasterizeTriangle(chunk.setups[i], context, target);
      }
      for (const uint32_t i : line_bins_[index]) {
        if (options.antialiasing == Antialiasing::kOff) {
          DrawLine(lines_[i], target);
        } else {
          DrawSmoothLine(lines_[i], target);
        }
      }
    }
    if (last_pass) {
      CopyOut(target, options.keep_depth, framebuffer);
    } else {
      SaveTile(target, &between_passes_);
    }
  });
}

}  // namespace flagsim::render
