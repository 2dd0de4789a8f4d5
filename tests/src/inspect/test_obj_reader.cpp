// Tests of src/inspect/obj_reader: valid variants are read exactly, every kind of bad input is a
// thaw::UserError naming the file and line.
#include "src/inspect/obj_reader.h"

#include <gtest/gtest.h>

#include "src/common/error.h"
#include "tests/src/inspect/test_meshes.h"

namespace thaw::inspect {
namespace {

const std::filesystem::path kData = std::filesystem::path(THAW_SOURCE_DIR) / "tests/src/inspect/data";

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
  testing::ScratchDir dir("obj");
  const TriangleMesh m = testing::icosphere(0.0123456789, 2, {1e-3, -2e-3, 0.5});
  write_obj(dir.path() / "s.obj", m);
  const TriangleMesh back = read_obj(dir.path() / "s.obj");
  EXPECT_EQ(back.vertices, m.vertices);  // 17 significant digits round-trip doubles exactly
  EXPECT_EQ(back.triangles, m.triangles);
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
  EXPECT_THROW(read_obj(kData), UserError);
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
}  // namespace thaw::inspect
