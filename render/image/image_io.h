#pragma once
// Image files, always written atomically (temporary file + rename, base/atomic_file.h):
// PNG, 8- or 16-bit sRGB after scaling by 2^exposure and the view transform (clamping to
// [0, 1], or AgX: render/film/view_transform.h) (IEC 61966-2-1 transfer curve; encoded in parallel
// by render/image/png_encoder.h), PFM, linear 32-bit float RGB for HDR work (bottom row first,
// little endian), and EXR (render/image/exr_io.h).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "render/film/view_transform.h"
#include "render/image/image.h"

namespace thaw::render {

/// sRGB transfer curve of a linear value in [0, 1].
float linear_to_srgb(float v);
/// 8-bit sRGB of linear `v` scaled by `scale` (clamped, rounded to nearest).
std::uint8_t to_srgb8(float v, float scale = 1.0f);
/// to_srgb8(v) by a table of the 255 rounding thresholds (no pow): what encode_png uses.
std::uint8_t srgb8_by_table(float v);

/// 16-bit sRGB of linear `v` scaled by `scale` (clamped, rounded to nearest).
std::uint16_t to_srgb16(float v, float scale = 1.0f);

/// PNG bit depths thaw writes: 8 or 16 (the one rule the command line and scene files use).
bool valid_png_bits(int bits);

/// PNG file bytes of `image` (8- or 16-bit sRGB, exposure in stops).
std::string encode_png(const Image& image, double exposure = 0.0, int bits = 8,
                       ViewTransform view = ViewTransform::clip);
/// PFM file bytes of `image` (linear float).
std::string encode_pfm(const Image& image);

void write_png(const std::filesystem::path& path, const Image& image, double exposure = 0.0,
               int bits = 8, ViewTransform view = ViewTransform::clip);
void write_pfm(const std::filesystem::path& path, const Image& image);
/// Whether `path` names an EXR file (render/image/exr_io.h), by its extension.
bool is_exr_path(const std::filesystem::path& path);
/// Chooses the format by extension (.png, .pfm, or .exr: RGBA only, without AOV layers);
/// throws UserError for anything else.
/// `view` applies to PNG only: PFM and EXR stay linear.
void write_image(const std::filesystem::path& path, const Image& image, double exposure = 0.0,
                 int png_bits = 8, ViewTransform view = ViewTransform::clip);
/// Throws UserError unless `path` has a supported extension and a writable existing folder.
void check_output_path(const std::filesystem::path& path);

}  // namespace thaw::render
