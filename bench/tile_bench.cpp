// Time to encode one frame into tiles (hash every tile, compress the changed ones, the manifest):
// the breeze flag at 64 x 48 nodes drawn at 1280 x 720 after 500 steps and again 8 steps later,
// the two images encoded in turn, so that each frame sends the tiles the flag moved through.
//
//   build/bench/tile_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include "server/service/frame_painter.hpp"
#include "server/service/session.hpp"
#include "server/service/tile_stream.hpp"

namespace flagsim {
namespace {

void BM_EncodeFrame(benchmark::State& bench) {
  const int threads = int(bench.range(0));
  Scene scene;
  scene.sim.cols = 64;
  scene.sim.rows = 48;
  Session session(scene);
  for (int i = 0; i < 500; ++i) session.Step();
  FramePainter painter;
  const render::Framebuffer before = painter.Paint(FrameInput::Of(session, 0), 1);
  for (int i = 0; i < 8; ++i) session.Step();
  const render::Framebuffer after = painter.Paint(FrameInput::Of(session, 0), 1);
  TileStream tiles;
  int64_t frames = 0;
  double tiles_sent = 0;
  for (auto _ : bench) {
    tiles_sent += double(tiles.Encode(frames++ % 2 ? before : after, FrameInfo{}, threads).tiles.size());
  }
  bench.counters["tiles_per_frame"] = tiles_sent / double(frames);
}

BENCHMARK(BM_EncodeFrame)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);

/// A keyframe (every tile, as a REFRESH asks) of the same 1280 x 720 picture.
void BM_EncodeKeyframe(benchmark::State& bench) {
  const int threads = int(bench.range(0));
  Scene scene;
  Session session(scene);
  for (int i = 0; i < 500; ++i) session.Step();
  FramePainter painter;
  const render::Framebuffer image = painter.Paint(FrameInput::Of(session, 0), 1);
  TileStream tiles;
  double bytes = 0;
  int64_t frames = 0;
  for (auto _ : bench) {
    tiles.RequestKeyframe(frames++);
    bytes += double(tiles.Encode(image, FrameInfo{}, threads).encoded_bytes);
  }
  bench.counters["bytes_per_keyframe"] = bytes / double(frames);
}

BENCHMARK(BM_EncodeKeyframe)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace flagsim

BENCHMARK_MAIN();
