// Tests of base/obj_reader (and its writer's round trip): valid variants are read exactly,
// every kind of bad input is a thaw::UserError naming the file and line (issue 12: malformed OBJ
// that tinyobjloader accepted).
#include "base/obj_reader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include "base/error.h"
#include "base/obj_writer.h"
#include "tests/src/inspect/icosphere.h"

namespace thaw::meshio {
namespace {

const std::filesystem::path kData =
    std::filesystem::path(THAW_SOURCE_DIR) / "tests/src/inspect/data";

/// Runs parse_obj and returns the UserError's where() + ": " + problem(), or "" if none.
std::string error_of(const std::string& text) {
  try {
    parse_obj(text, "test.obj");
  } catch (const UserError& e) {
    EXPECT_EQ(e.file(), "test.obj");
    return e.where() + ": " + e.problem();
  }
  return "";
}

TEST(ObjReader, ReadsCube) {
  const TriangleMesh m = read_obj(kData / "cube.obj");
  ASSERT_EQ(m.vertices.size(), 8u);
  ASSERT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.vertices[6], (std::array<double, 3>{2, 2, 2}));
  EXPECT_EQ(m.triangles[0], (std::array<std::int64_t, 3>{0, 2, 1}));  // "f 1 3 2", 0-based
}

TEST(ObjReader, QuadsRelativeIndicesAndAttributesBecomeTheSameTriangles) {
  const TriangleMesh m = read_obj(kData / "cube_quads.obj");
  ASSERT_EQ(m.triangles.size(), 12u);
  // "f -7 -6 -2 -3" after 8 vertices is the quad 2 3 7 6 -> fan (2 3 7), (2 7 6), 0-based.
  EXPECT_EQ(m.triangles[10], (std::array<std::int64_t, 3>{1, 2, 6}));
  EXPECT_EQ(m.triangles[11], (std::array<std::int64_t, 3>{1, 6, 5}));
}

TEST(ObjReader, WriteReadRoundTripIsExact) {
  const TriangleMesh m = inspect::testing::icosphere(0.0123456789, 2, {1e-3, -2e-3, 0.5});
  const TriangleMesh back = parse_obj(format_obj(m, "a comment"), "s.obj");
  EXPECT_EQ(back.vertices, m.vertices);  // 17 significant digits round-trip doubles exactly
  EXPECT_EQ(back.triangles, m.triangles);
  EXPECT_TRUE(back.normals.empty());
  EXPECT_TRUE(back.normal_triangles.empty());
  // On disk too (atomic write), with normals: 9 digits round-trip floats.
  const auto path = std::filesystem::path(THAW_BINARY_DIR) /
                    ("meshio_round_trip_" + std::to_string(::getpid()) + ".obj");
  TriangleMesh with_normals = m;
  for (const auto& v : m.vertices)
    with_normals.normals.push_back({float(v[0]), float(v[1]), 0.25f});
  with_normals.normal_triangles = m.triangles;
  write_obj(path, with_normals);
  const TriangleMesh read = read_obj(path);
  std::filesystem::remove(path);
  ASSERT_EQ(read.normals.size(), with_normals.normals.size());
  for (std::size_t i = 0; i < read.normals.size(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(float(read.normals[i][k]), float(with_normals.normals[i][k])) << i;
  EXPECT_EQ(read.normal_triangles, with_normals.normal_triangles);
}

TEST(ObjReader, BadFixturesNameFileAndLine) {
  struct Case {
    const char* file;
    const char* where;
    const char* problem_part;
  };
  for (const Case& c : {Case{"bad_index.obj", "line 10", "vertex 9"},
                        Case{"nan_coordinate.obj", "line 3", "non-finite"},
                        Case{"junk_statement.obj", "line 4", "unknown OBJ statement 'hello'"},
                        Case{"empty.obj", "", "empty mesh"}}) {
    SCOPED_TRACE(c.file);
    try {
      read_obj(kData / c.file);
      ADD_FAILURE() << "no error";
    } catch (const UserError& e) {
      EXPECT_EQ(e.file(), (kData / c.file).string());
      EXPECT_EQ(e.where(), c.where);
      EXPECT_NE(e.problem().find(c.problem_part), std::string::npos) << e.what();
    }
  }
}

TEST(ObjReader, MissingFileAndDirectoryAreUserErrors) {
  EXPECT_THROW(read_obj(kData / "no_such_file.obj"), UserError);
  try {
    read_obj(kData);
    ADD_FAILURE() << "no error";
  } catch (const UserError& e) {
    EXPECT_EQ(e.problem(), "is a directory, expected an OBJ file");
  }
}

TEST(ObjReader, DeviceIsNotReadForever) {
  try {
    read_obj("/dev/zero");
    ADD_FAILURE() << "no error";
  } catch (const UserError& e) {
    EXPECT_EQ(e.problem(), "is not a regular file, expected an OBJ file");
  }
}

// The malformed files of issue 12 that the renderer used to accept.
TEST(ObjReader, RejectsWhatTinyobjloaderAccepted) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  // 4294967298 = 2^32 + 2 wrapped to index 2 in 32 bits.
  EXPECT_EQ(error_of(tri + "f 1 2 4294967298\n"),
            "line 4: face refers to vertex 4294967298 but the file has only 3 vertices");
  EXPECT_EQ(error_of(tri + "f 1 2 99999999999999999999999\n"),
            "line 4: vertex index '99999999999999999999999' is out of range");
  EXPECT_EQ(error_of(tri + "f 1 2\n"), "line 4: face needs at least 3 corners, got 2");
  EXPECT_EQ(error_of(tri + "f 1 2 3 junk\n"), "line 4: malformed vertex index 'junk'");
  EXPECT_EQ(error_of("v 0 0 0 0 junk\n"), "line 1: vertex needs 3 coordinates, got 5 numbers");
  EXPECT_EQ(error_of(tri + "f 1 2 1.5\n"), "line 4: malformed vertex index '1.5'");
  EXPECT_EQ(error_of(tri + "f 1 2 3e0\n"), "line 4: malformed vertex index '3e0'");
  EXPECT_EQ(error_of(tri + "f 1 2 +3\n"), "line 4: malformed vertex index '+3'");
  EXPECT_EQ(error_of(tri + "f 1 2 3"),
            "line 4: last line has no line end: the file looks truncated");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1"),
            "line 3: last line has no line end: the file looks truncated");
  // A comment or blank space after the last line end is not a truncated statement.
  EXPECT_EQ(error_of(tri + "f 1 2 3\n# end"), "");
  EXPECT_EQ(error_of(tri + "f 1 2 3\n  "), "");
}

TEST(ObjReader, NormalsAreKeptWhenEveryCornerHasOne) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 2\n";
  const TriangleMesh m = parse_obj(tri + "f 1//1 2//2 3//1\n", "n.obj");
  ASSERT_EQ(m.normals.size(), 2u);
  EXPECT_EQ(m.normals[1], (std::array<double, 3>{0, 0, 2}));
  ASSERT_EQ(m.normal_triangles.size(), 1u);
  EXPECT_EQ(m.normal_triangles[0], (std::array<std::int64_t, 3>{0, 1, 0}));
  // One corner without a normal: no normals at all (flat shading), not a partial set.
  const TriangleMesh partial = parse_obj(tri + "f 1//1 2//2 3//1\nf 1 2 3\n", "n.obj");
  EXPECT_TRUE(partial.normal_triangles.empty());
  EXPECT_TRUE(partial.normals.empty());
  EXPECT_EQ(error_of(tri + "f 1//3 2//2 3//1\n"),
            "line 6: face refers to normal 3 but the file has only 2");
  EXPECT_EQ(error_of("vn 0 0\n"), "line 1: normal needs 3 numbers, got 2");
  EXPECT_EQ(error_of("vt 0 nan\n"), "line 1: non-finite coordinate 'nan'");
}

TEST(ObjReader, MalformedStatements) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_EQ(error_of(tri + "f 1 2 0\n"), "line 4: vertex index 0 (OBJ indices start at 1)");
  EXPECT_EQ(error_of(tri + "f 1 2\n"), "line 4: face needs at least 3 corners, got 2");
  EXPECT_EQ(error_of("v 0 0\n"), "line 1: vertex needs 3 coordinates, got 2 numbers");
  EXPECT_EQ(error_of("v 0 0 1.5x\n"), "line 1: malformed number '1.5x'");
  EXPECT_EQ(error_of("v 0 inf 0\n"), "line 1: non-finite coordinate 'inf'");
  EXPECT_EQ(error_of(tri + "f 1 2 -4\n"),
            "line 4: relative vertex index -4 points before the first vertex (only 3 so far)");
  EXPECT_EQ(error_of(tri + "f 1 2 x\n"), "line 4: malformed vertex index 'x'");
  EXPECT_EQ(error_of(tri + "f 1/1 2/1 3/1\n"),
            "line 4: face refers to texture coordinate 1 but the file has only 0");
  EXPECT_EQ(error_of(tri + "f 1/ 2/ 3/\n"), "line 4: malformed face corner '1/'");
  EXPECT_EQ(error_of(""), ": empty mesh: no faces (0 vertices)");
  // Comments, blank lines, CRLF line ends and a leading '+' are fine.
  EXPECT_EQ(error_of("# c\r\n\r\nv +0 0 0\r\nv 1 0 0 # x\r\nv 0 1 0\r\nf 1 2 3\r\n"), "");
}

}  // namespace
}  // namespace thaw::meshio
