// The distortion warp's CPU part on a software renderer (issue 24): which cells of the 32x20 mesh
// have anything on them (WarpCellScan over the ideal render read back from the GPU), for the
// issue's wide-angle lens (k1 = -0.2, k2 = 0.05) on its 1280x800, f = 1900 projector: the ideal
// render is then 1382x864. Pictures: empty (black), a projector's usual picture (arrows: ~10% of
// the pixels lit, in bands), and full. Baseline in the same run: copying the picture once (what
// the read-back itself costs at least).
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include <benchmark/benchmark.h>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/warp_cells.h"
#include "rviz_projector/core/warp_grid.h"

namespace
{
using namespace rviz_projector;

const WarpGrid& wideGrid()
{
  static const WarpGrid grid = makeWarpGrid(PinholeModel(1280, 800, 1900.0, 1900.0, 639.5, 399.5),
                                            LensDistortion(LensDistortion::Model::PlumbBob, {-0.2, 0.05, 0, 0, 0}));
  return grid;
}

/// 0: empty, 1: arrows-like bands over the middle (~10% lit), 2: every pixel lit.
std::vector<std::uint32_t> picture(int kind)
{
  const WarpGrid& g = wideGrid();
  const std::uint32_t w = g.ideal_lens.width(), h = g.ideal_lens.height();
  std::vector<std::uint32_t> pixels(std::size_t(w) * h, kind == 2 ? 0xFF00FF00u : 0xFF000000u);
  if (kind == 1)
  {
    for (std::uint32_t y = 0; y < h; ++y)
    {
      for (std::uint32_t x = w * 2 / 5; x < w * 3 / 5 && (y / 40) % 2 == 0; ++x)
      {
        pixels[std::size_t(y) * w + x] = 0xFFFF00FFu;
      }
    }
  }
  return pixels;
}

void BM_PictureCopyBaseline(benchmark::State& state)
{
  const std::vector<std::uint32_t> pixels = picture(1);
  std::vector<std::uint32_t> copy(pixels.size());
  for (auto _ : state)
  {
    std::memcpy(copy.data(), pixels.data(), pixels.size() * sizeof(std::uint32_t));
    benchmark::DoNotOptimize(copy.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * pixels.size() * sizeof(std::uint32_t)));
}

void scanCells(benchmark::State& state, int kind)
{
  const WarpGrid& g = wideGrid();
  const std::vector<std::uint32_t> pixels = picture(kind);
  WarpCellScan scan(g);
  std::vector<std::uint8_t> occupied;
  std::size_t drawn = 0;
  for (auto _ : state)
  {
    drawn = scan.scan(pixels.data(), g.ideal_lens.width(), g.ideal_lens.height(), g.ideal_lens.width(), 0xFF000000u,
                      0x00FFFFFFu, occupied);
    benchmark::DoNotOptimize(occupied.data());
  }
  state.counters["cells drawn"] = static_cast<double>(drawn);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * pixels.size() * sizeof(std::uint32_t)));
  state.SetLabel("vs=Baseline/PictureCopy");
}

// The read-back and the scan together, as the display does them: the whole picture copied out (the
// "texture" stands for the renderer's memory) then scanned, against strips of `rows` rows copied
// into one small buffer and each scanned at once (while it is in the cache).
void copyAndScan(benchmark::State& state, std::uint32_t rows)
{
  const WarpGrid& g = wideGrid();
  const std::vector<std::uint32_t> texture = picture(1);
  const std::uint32_t w = g.ideal_lens.width(), h = g.ideal_lens.height();
  std::vector<std::uint32_t> buffer(rows == 0 ? texture.size() : std::size_t(w) * rows);
  WarpCellScan scan(g);
  std::vector<std::uint8_t> occupied;
  std::size_t drawn = 0;
  for (auto _ : state)
  {
    if (rows == 0)
    {
      std::memcpy(buffer.data(), texture.data(), texture.size() * sizeof(std::uint32_t));
      drawn = scan.scan(buffer.data(), w, h, w, 0xFF000000u, 0x00FFFFFFu, occupied);
    }
    else
    {
      scan.begin(0xFF000000u, 0x00FFFFFFu);
      for (std::uint32_t y = 0; y < h; y += rows)
      {
        const std::uint32_t n = std::min(rows, h - y);
        std::memcpy(buffer.data(), texture.data() + std::size_t(y) * w, std::size_t(n) * w * sizeof(std::uint32_t));
        scan.addRows(buffer.data(), y, n, w);
      }
      drawn = scan.finish(occupied);
    }
    benchmark::DoNotOptimize(occupied.data());
  }
  state.counters["cells drawn"] = static_cast<double>(drawn);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * texture.size() * sizeof(std::uint32_t)));
  state.SetLabel(rows == 0 ? "vs=Baseline/PictureCopy" : "vs=WarpCells/Copy+scan whole");
}

void BM_WarpCellScanEmpty(benchmark::State& state) { scanCells(state, 0); }
void BM_WarpCellScanArrows(benchmark::State& state) { scanCells(state, 1); }
void BM_WarpCellScanFull(benchmark::State& state) { scanCells(state, 2); }

constexpr int kIdealPixels = 1382 * 864;  // the size column: pixels of the ideal render
}  // namespace

BENCHMARK(BM_PictureCopyBaseline)->Name("Baseline/PictureCopy")->Arg(kIdealPixels)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WarpCellScanEmpty)->Name("WarpCells/Scan empty")->Arg(kIdealPixels)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WarpCellScanArrows)->Name("WarpCells/Scan arrows")->Arg(kIdealPixels)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WarpCellScanFull)->Name("WarpCells/Scan full")->Arg(kIdealPixels)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(copyAndScan, whole, 0u)->Name("WarpCells/Copy+scan whole")->Arg(kIdealPixels)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(copyAndScan, strips, 64u)
    ->Name("WarpCells/Copy+scan 64-row strips")
    ->Arg(kIdealPixels)
    ->Unit(benchmark::kMicrosecond);
