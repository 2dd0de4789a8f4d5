#include "render/image/exr_io.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfStringVectorAttribute.h>
#include <omp.h>

#include <vector>

#include "base/atomic_file.h"
#include "base/check.h"
#include "thaw_version.h"

namespace thaw::render {
namespace {

/// One channel's pixels, kept alive until the file is written.
struct Plane {
  std::string name;
  Imf::PixelType type;
  std::vector<half> halves;
  std::vector<float> floats;
};

Plane half_plane(std::string name, std::size_t n) {
  Plane p{std::move(name), Imf::HALF, std::vector<half>(n), {}};
  return p;
}
Plane float_plane(std::string name, std::size_t n) {
  Plane p{std::move(name), Imf::FLOAT, {}, std::vector<float>(n)};
  return p;
}

std::vector<Plane> planes_of(const Image& image, const AovImage* aovs) {
  const std::size_t n = image.pixels().size();
  std::vector<Plane> planes;
  for (const char* c : {"R", "G", "B", "A"}) planes.push_back(half_plane(c, n));
  if (aovs) {
    planes.push_back(float_plane("Z", n));
    for (const char* c : {"N.X", "N.Y", "N.Z"}) planes.push_back(half_plane(c, n));
    for (const char* c : {"id.object", "id.medium"}) planes.push_back(float_plane(c, n));
  }
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const Rgb& c = image.pixels()[i];
    // half(float) rounds to nearest even: relative error <= 2^-11 in the normal range.
    planes[0].halves[i] = half(c.r);
    planes[1].halves[i] = half(c.g);
    planes[2].halves[i] = half(c.b);
    planes[3].halves[i] = half(aovs ? aovs->alpha[i] : 1.0f);
    if (!aovs) continue;
    planes[4].floats[i] = aovs->depth[i];
    for (int a = 0; a < 3; ++a) planes[5 + a].halves[i] = half(aovs->normal[i][a]);
    planes[8].floats[i] = static_cast<float>(aovs->object_id[i]);
    planes[9].floats[i] = static_cast<float>(aovs->medium_id[i]);
  }
  return planes;
}

void add_metadata(Imf::Header& header, const ExrMetadata& m, const AovImage* aovs) {
  header.insert("software", Imf::StringAttribute(std::string("thaw ") + THAW_VERSION_STRING));
  header.insert("thaw.sceneFile", Imf::StringAttribute(m.scene_file));
  if (m.time_s) header.insert("thaw.simulatedTime_s", Imf::DoubleAttribute(*m.time_s));
  header.insert("thaw.samplesPerPixel", Imf::IntAttribute(m.samples_per_pixel));
  header.insert("thaw.exposure_stops", Imf::DoubleAttribute(m.exposure_stops));
  if (aovs) {
    header.insert("thaw.objectIds", Imf::StringVectorAttribute(aovs->object_names));
    header.insert("thaw.mediumIds", Imf::StringVectorAttribute(aovs->medium_names));
  }
  // Imath's matrices act on row vectors: M44f[i][j] = M[j][i].
  const auto imath = [](const ExrMetadata::Matrix4& m) {
    Imath::M44f t;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) t[i][j] = static_cast<float>(m[4 * j + i]);
    return t;
  };
  if (m.world_to_camera) Imf::addWorldToCamera(header, imath(*m.world_to_camera));
  if (m.world_to_ndc) Imf::addWorldToNDC(header, imath(*m.world_to_ndc));
}

}  // namespace

std::string encode_exr(const Image& image, const AovImage* aovs, const ExrMetadata& metadata) {
  const int w = image.width(), h = image.height();
  THAW_CHECK(w > 0 && h > 0, "EXR of an empty image");
  THAW_CHECK(!aovs || (aovs->width == w && aovs->height == h), "AOVs and image differ in size");
  const std::vector<Plane> planes = planes_of(image, aovs);
  Imf::Header header(w, h);
  header.compression() = Imf::ZIP_COMPRESSION;
  add_metadata(header, metadata, aovs);
  Imf::FrameBuffer fb;
  for (const Plane& p : planes) {
    header.channels().insert(p.name, Imf::Channel(p.type));
    const std::size_t size = p.type == Imf::HALF ? sizeof(half) : sizeof(float);
    const char* base = p.type == Imf::HALF ? reinterpret_cast<const char*>(p.halves.data())
                                           : reinterpret_cast<const char*>(p.floats.data());
    fb.insert(p.name, Imf::Slice(p.type, const_cast<char*>(base), size, size * std::size_t(w)));
  }
  Imf::StdOSStream stream;
  {
    // The file's blocks are compressed on OpenEXR's own thread pool, one thread per core.
    Imf::OutputFile file(stream, header, omp_get_max_threads());
    file.setFrameBuffer(fb);
    file.writePixels(h);
  }
  return stream.str();
}

void write_exr(const std::filesystem::path& path, const Image& image, const AovImage* aovs,
               const ExrMetadata& metadata) {
  write_file_atomic(path, encode_exr(image, aovs, metadata));
}

}  // namespace thaw::render
