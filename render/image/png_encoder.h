#pragma once
// A fast, standard PNG encoder for 8- and 16-bit RGB/RGBA samples (knows nothing about colour
// or float images: render/image/image_io.h does the sRGB encoding). Fast because it compresses
// in parallel: the rows are cut into bands, each band is filtered (a filter chosen per row by
// the minimum-sum-of-absolute-differences heuristic of the PNG specification, section 12.8) and
// deflated independently by zlib at a low level, and the raw deflate streams are concatenated
// (every band but the last ends with a byte-aligned Z_SYNC_FLUSH and no final-block bit, so the
// concatenation is one valid deflate stream; the zlib trailer's Adler-32 is combined from the
// bands' with adler32_combine). The approach of pigz (Mark Adler), applied to PNG rows. Any PNG
// decoder reads the result; the price of independent bands is a few hundred bytes per band.
#include <cstdint>
#include <string>

namespace thaw::render {

struct PngLayout {
  int width = 0, height = 0;
  /// 3 (RGB) or 4 (RGBA)
  int channels = 3;
  /// 8 or 16; 16-bit samples are given in native order and stored big-endian as PNG requires
  int bit_depth = 8;
  /// zlib level of the bands, 1 (fastest) to 9. 2 by default: measured on S4 at 2000x2000
  /// (bench/render/bench_image_io.cpp, docs/benchmarks.md), higher levels cost several times
  /// the time for files only slightly smaller.
  int deflate_level = 2;
};

/// PNG file bytes of `samples`: height rows of width * channels samples, top row first, each
/// sample a std::uint8_t (bit_depth 8) or a std::uint16_t (bit_depth 16) in native byte order.
/// `threads` = 0: the OpenMP default.
std::string encode_png_samples(const void* samples, const PngLayout& layout, int threads = 0);

}  // namespace thaw::render
