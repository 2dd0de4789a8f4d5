// Tests of the OBJ contract (src/mesh/obj_writer.h): exact text, 17-digit round trip, normals.
#include "src/mesh/obj_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace thaw::mesh {
namespace {

TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

TEST(ObjWriter, ExactTextWithoutNormals) {
  EXPECT_EQ(format_obj(tetrahedron(), "t"),
            "# t\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
}

TEST(ObjWriter, NormalsUseDoubleSlashFaces) {
  TriangleMesh m = tetrahedron();
  m.normals.assign(4, {0, 0, 1});
  const std::string text = format_obj(m);
  EXPECT_NE(text.find("vn 0 0 1\n"), std::string::npos);
  EXPECT_NE(text.find("f 2//2 3//3 4//4\n"), std::string::npos);
}

TEST(ObjWriter, SeventeenDigitsRoundTripExactly) {
  TriangleMesh m = tetrahedron();
  m.vertices[1] = {0.1, 1.0 / 3.0, -2.0e-7 / 3.0};
  std::istringstream in(format_obj(m));
  std::string line;
  std::getline(in, line);
  std::getline(in, line);  // second vertex
  std::istringstream v(line.substr(2));
  for (double expected : m.vertices[1]) {
    std::string token;
    v >> token;
    EXPECT_EQ(std::strtod(token.c_str(), nullptr), expected) << token;
  }
}

TEST(ObjWriter, EnclosedVolumeOfOutwardTetrahedron) {
  // Unit right tetrahedron: volume 1/6, positive when faces are counter-clockwise from outside.
  EXPECT_NEAR(enclosed_volume(tetrahedron()), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(surface_area(tetrahedron()), 1.5 + std::sqrt(3.0) / 2, 1e-15);
}

TEST(ObjWriter, WritesAtomically) {
  const auto dir = std::filesystem::path(THAW_BINARY_DIR) / "test_obj_writer";
  std::filesystem::create_directories(dir);
  write_obj(dir / "t.obj", tetrahedron());
  std::ifstream in(dir / "t.obj");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), format_obj(tetrahedron()));
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

// Buffers reused from a larger mesh with normals for a smaller one without: the same bytes as a
// fresh write, nothing left over from the first mesh (no stale normals, lines or "//" faces).
TEST(ObjWriter, ReusedBuffersWriteTheSameBytes) {
  const auto dir = std::filesystem::path(THAW_BINARY_DIR) / "test_obj_writer_buffers";
  std::filesystem::create_directories(dir);
  TriangleMesh big = tetrahedron();
  big.vertices.push_back({2, 2, 2});
  big.faces.push_back({1, 2, 4});
  big.normals.assign(big.vertices.size(), {0, 1, 0});
  ObjBuffers buffers;
  write_obj(dir / "big.obj", big, "big", buffers);
  write_obj(dir / "small.obj", tetrahedron(), "t", buffers);
  const auto text = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  EXPECT_EQ(text(dir / "big.obj"), format_obj(big, "big"));
  EXPECT_EQ(text(dir / "small.obj"), format_obj(tetrahedron(), "t"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace thaw::mesh
