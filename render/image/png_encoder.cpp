#include "render/image/png_encoder.h"

#include <omp.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "base/check.h"

namespace thaw::render {
namespace {

/// Raw (filter-free) bytes of one row as PNG stores them: 16-bit samples big-endian.
void row_bytes(const void* samples, const PngLayout& l, int y, std::uint8_t* out) {
  const std::size_t n = std::size_t(l.width) * l.channels;
  if (l.bit_depth == 8) {
    std::memcpy(out, static_cast<const std::uint8_t*>(samples) + std::size_t(y) * n, n);
    return;
  }
  const std::uint16_t* row = static_cast<const std::uint16_t*>(samples) + std::size_t(y) * n;
  for (std::size_t i = 0; i < n; ++i) {
    out[2 * i] = static_cast<std::uint8_t>(row[i] >> 8);
    out[2 * i + 1] = static_cast<std::uint8_t>(row[i] & 0xffu);
  }
}

/// PNG's Paeth predictor (specification 9.4): the neighbour closest to a + b - c, ties in the
/// order a, b, c. Written with selects only, so the row loops below vectorise.
/// Every intermediate fits 16 bits (bytes 0..255: |a + b - 2c| <= 510), so the loops vectorise
/// with 16-bit lanes.
inline int paeth(int a, int b, int c) {
  const auto pa = static_cast<std::int16_t>(std::abs(b - c));
  const auto pb = static_cast<std::int16_t>(std::abs(a - c));
  const auto pc = static_cast<std::int16_t>(std::abs(a + b - 2 * c));
  const auto bc = static_cast<std::int16_t>(pb <= pc ? b : c);
  return static_cast<std::int16_t>((pa <= pb && pa <= pc) ? a : bc);
}

/// The five filtered values (none, sub, up, average, Paeth) of byte x with left a, up b, up-left c.
struct Filtered {
  std::int16_t v[5];
};
inline Filtered filter_byte(int x, int a, int b, int c) {
  return {{static_cast<std::int16_t>(x), static_cast<std::int16_t>(x - a),
           static_cast<std::int16_t>(x - b), static_cast<std::int16_t>(x - ((a + b) >> 1)),
           static_cast<std::int16_t>(x - paeth(a, b, c))}};
}
inline std::uint32_t abs_signed_byte(int v) {
  return static_cast<std::uint32_t>(std::abs(static_cast<int>(static_cast<std::int8_t>(v))));
}

/// Filters `row` (prior row `up`, zeros above the image) with the one of the five PNG filters
/// whose filtered bytes have the smallest sum of |signed byte| (PNG specification 12.8; the first
/// of equals) and writes it to `out`: filter type byte, then the filtered row. Two passes: the
/// five sums without storing anything, then the chosen filter's bytes.
void filter_row(const std::uint8_t* row, const std::uint8_t* up, std::size_t n, std::size_t bpp,
                std::uint8_t* out) {
  const std::size_t head = std::min(bpp, n);  // the first pixel: no left neighbours (a = c = 0)
  std::uint64_t cost[5] = {0, 0, 0, 0, 0};
  for (std::size_t i = 0; i < head; ++i) {
    const Filtered f = filter_byte(row[i], 0, up[i], 0);
    for (int k = 0; k < 5; ++k) cost[k] += abs_signed_byte(f.v[k]);
  }
  // 32-bit sums over chunks of 2^20 bytes (at most 128 x 2^20 = 2^27 each), which vectorise.
  for (std::size_t start = head; start < n; start += std::size_t(1) << 20) {
    const std::size_t end = std::min(n, start + (std::size_t(1) << 20));
    std::uint32_t c0 = 0, c1 = 0, c2 = 0, c3 = 0, c4 = 0;
    for (std::size_t i = start; i < end; ++i) {
      const Filtered f = filter_byte(row[i], row[i - bpp], up[i], up[i - bpp]);
      c0 += abs_signed_byte(f.v[0]);
      c1 += abs_signed_byte(f.v[1]);
      c2 += abs_signed_byte(f.v[2]);
      c3 += abs_signed_byte(f.v[3]);
      c4 += abs_signed_byte(f.v[4]);
    }
    cost[0] += c0, cost[1] += c1, cost[2] += c2, cost[3] += c3, cost[4] += c4;
  }
  int best = 0;
  for (int f = 1; f < 5; ++f)
    if (cost[f] < cost[best]) best = f;
  out[0] = static_cast<std::uint8_t>(best);
  std::uint8_t* o = out + 1;
  for (std::size_t i = 0; i < head; ++i)
    o[i] = static_cast<std::uint8_t>(filter_byte(row[i], 0, up[i], 0).v[best]);
  // One loop per filter, so that each vectorises.
  const auto write = [&](auto&& filter) {
    for (std::size_t i = head; i < n; ++i)
      o[i] = static_cast<std::uint8_t>(filter(row[i], row[i - bpp], up[i], up[i - bpp]));
  };
  switch (best) {
    case 0:
      std::memcpy(o + head, row + head, n - head);
      break;
    case 1:
      write([](int x, int a, int, int) { return x - a; });
      break;
    case 2:
      write([](int x, int, int b, int) { return x - b; });
      break;
    case 3:
      write([](int x, int a, int b, int) { return x - ((a + b) >> 1); });
      break;
    default:
      write([](int x, int a, int b, int c) { return x - paeth(a, b, c); });
      break;
  }
}

struct Band {
  int first_row = 0, rows = 0;
  std::string deflated;
  /// Adler-32 of the band's filtered bytes and their count
  uLong adler = 1;
  std::size_t filtered_bytes = 0;
  bool ok = true;
};

/// Filters and deflates one band of rows: a raw deflate stream ending in a sync flush (or in the
/// final block if `last`).
void compress_band(const void* samples, const PngLayout& l, bool last, Band& band) {
  const std::size_t bpp = std::size_t(l.channels) * (l.bit_depth / 8);
  const std::size_t n = std::size_t(l.width) * bpp;
  std::vector<std::uint8_t> prev(n, 0), cur(n), filtered(std::size_t(band.rows) * (n + 1));
  if (band.first_row > 0) row_bytes(samples, l, band.first_row - 1, prev.data());
  for (int r = 0; r < band.rows; ++r) {
    row_bytes(samples, l, band.first_row + r, cur.data());
    filter_row(cur.data(), prev.data(), n, bpp, filtered.data() + std::size_t(r) * (n + 1));
    std::swap(prev, cur);
  }
  band.filtered_bytes = filtered.size();
  band.adler = adler32(adler32(0L, Z_NULL, 0), filtered.data(), static_cast<uInt>(filtered.size()));

  z_stream zs{};
  // windowBits -15: a raw deflate stream (the zlib header and trailer are written once, around
  // all bands).
  if (deflateInit2(&zs, l.deflate_level, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    band.ok = false;
    return;
  }
  band.deflated.resize(deflateBound(&zs, filtered.size()) + 16);  // + the sync flush's 5 bytes
  zs.next_in = filtered.data();
  zs.avail_in = static_cast<uInt>(filtered.size());
  zs.next_out = reinterpret_cast<Bytef*>(band.deflated.data());
  zs.avail_out = static_cast<uInt>(band.deflated.size());
  const int rc = deflate(&zs, last ? Z_FINISH : Z_SYNC_FLUSH);
  band.ok = (last ? rc == Z_STREAM_END : rc == Z_OK) && zs.avail_in == 0 && zs.avail_out > 0;
  band.deflated.resize(zs.total_out);
  deflateEnd(&zs);
}

void put_u32(std::string& s, std::uint32_t v) {
  const char b[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                     static_cast<char>(v >> 8), static_cast<char>(v)};
  s.append(b, 4);
}

void put_chunk(std::string& png, const char* type, const std::string& data) {
  put_u32(png, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = png.size();
  png.append(type, 4);
  png += data;
  const uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(png.data() + start),
                          static_cast<uInt>(png.size() - start));
  put_u32(png, static_cast<std::uint32_t>(crc));
}

}  // namespace

std::string encode_png_samples(const void* samples, const PngLayout& l, int threads) {
  THAW_CHECK(l.width > 0 && l.height > 0, "PNG of an empty image");
  THAW_CHECK(l.channels == 3 || l.channels == 4, "PNG channels must be 3 or 4");
  THAW_CHECK(l.bit_depth == 8 || l.bit_depth == 16, "PNG bit depth must be 8 or 16");
  const std::size_t row_size = std::size_t(l.width) * l.channels * (l.bit_depth / 8) + 1;
  // Bands of about 256 KiB of filtered rows: enough for deflate's 32 KiB window to pay off, and
  // a fixed size, so the file does not depend on the thread count.
  const int band_rows = static_cast<int>(
      std::clamp<std::size_t>((std::size_t(256) << 10) / row_size, 1, std::size_t(l.height)));
  std::vector<Band> bands;
  for (int y = 0; y < l.height; y += band_rows) {
    Band b;
    b.first_row = y;
    b.rows = std::min(band_rows, l.height - y);
    bands.push_back(std::move(b));
  }
  const int count = static_cast<int>(bands.size());
#pragma omp parallel for schedule(dynamic, 1) \
    num_threads(threads > 0 ? threads : omp_get_max_threads()) if (count > 1)
  for (int i = 0; i < count; ++i)
    compress_band(samples, l, i == count - 1, bands[static_cast<std::size_t>(i)]);
  for (const Band& b : bands) THAW_CHECK(b.ok, "zlib deflate failed");

  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  put_u32(ihdr, static_cast<std::uint32_t>(l.width));
  put_u32(ihdr, static_cast<std::uint32_t>(l.height));
  const char ihdr_tail[5] = {static_cast<char>(l.bit_depth),
                             static_cast<char>(l.channels == 4 ? 6 : 2), 0, 0, 0};
  ihdr.append(ihdr_tail, 5);
  put_chunk(png, "IHDR", ihdr);
  // One IDAT per band: the zlib header (RFC 1950: CM 8, 32 KiB window, FLEVEL 0 "fastest",
  // FCHECK making 0x7801 a multiple of 31) before the first, the combined Adler-32 after the last.
  uLong adler = bands[0].adler;
  for (std::size_t i = 1; i < bands.size(); ++i)
    adler = adler32_combine(adler, bands[i].adler, static_cast<z_off_t>(bands[i].filtered_bytes));
  for (std::size_t i = 0; i < bands.size(); ++i) {
    std::string data;
    if (i == 0) data = std::string("\x78\x01", 2);
    data += bands[i].deflated;
    if (i + 1 == bands.size()) put_u32(data, static_cast<std::uint32_t>(adler));
    put_chunk(png, "IDAT", data);
  }
  put_chunk(png, "IEND", "");
  return png;
}

}  // namespace thaw::render
