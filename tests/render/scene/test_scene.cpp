// Tests render/scene/scene.h: build_scene from code (the pipeline's path) and its checks.
#include "render/scene/scene.h"

#include <gtest/gtest.h>

#include <random>

#include "base/error.h"
#include "tests/render/test_util.h"

namespace thaw::render {
namespace {

SceneDescription shell_scene() {
  SceneDescription d;
  d.camera.position = {0, 0, 5};
  d.camera.look_at = {0, 0, 0};
  d.media = {test::medium("air", 1.0), test::medium("ice", 1.31), test::medium("water", 1.33)};
  d.add_dielectric_mesh(std::make_shared<TriangleMesh>(test::icosphere(3, 1.0f)), "ice", "air",
                        "outer");
  d.add_dielectric_mesh(std::make_shared<TriangleMesh>(test::icosphere(3, 0.7f)), "water", "ice",
                        "inner");
  return d;
}

// An index-matched dielectric (the same index on both sides, no absorption) is invisible: shadow
// rays pass through it (occluded() is false), as analytic sphere and as packed mesh triangles;
// a real interface still blocks them.
TEST(Scene, IndexMatchedInterfacesLetShadowRaysThrough) {
  for (const double inner : {1.0, 1.33}) {
    SceneDescription d;
    d.camera.position = {0, 0, 5};
    d.camera.look_at = {0, 0, 0};
    d.media = {test::medium("air", 1.0), test::medium("same", 1.0), test::medium("water", inner)};
    d.add_dielectric_mesh(std::make_shared<TriangleMesh>(test::icosphere(3, 1.0f)), "same", "air",
                          "mesh");
    ObjectDescription ball;
    ball.shape = ObjectDescription::Shape::sphere;
    ball.center = {3, 0, 0};
    ball.radius = 1.0;
    ball.inside = "water";
    ball.outside = "air";
    d.objects.push_back(ball);
    const Scene s = build_scene(d);
    EXPECT_TRUE(s.objects()[0].index_matched);
    EXPECT_EQ(s.objects()[1].index_matched, inner == 1.0);
    EXPECT_FALSE(s.occluded(Ray{{0, 5, 0}, {0, -10, 0}}));  // through the matched mesh
    EXPECT_EQ(s.occluded(Ray{{3, 5, 0}, {0, -10, 0}}), inner != 1.0);
    Hit hit;
    EXPECT_TRUE(s.intersect(Ray{{0, 5, 0}, {0, -1, 0}}, hit));  // camera rays still see it
  }
}

// light_unoccluded() is conservative: wherever it says no shadow ray can be occluded, none of 64
// rays from that origin to points of the light's ball is (Scene::occluded, the rays' own test);
// over the floor under a shell, a ball and a box it says so for most points but not all.
TEST(Scene, LightUnoccludedOnlyWhereNoShadowRayIsOccluded) {
  SceneDescription d = shell_scene();
  LightDescription l;
  l.kind = LightDescription::Kind::sphere;
  l.position = {-2, 4, 1};
  l.radius = 0.6;
  d.lights.push_back(l);
  MaterialDescription m;
  m.name = "grey";
  d.materials.push_back(m);
  ObjectDescription floor;
  floor.shape = ObjectDescription::Shape::plane;
  floor.point = {0, -1, 0};
  floor.normal = {0, 1, 0};
  floor.material = "grey";
  d.objects.push_back(floor);
  ObjectDescription ball;
  ball.shape = ObjectDescription::Shape::sphere;
  ball.center = {2, 0, 0};
  ball.radius = 0.5;
  ball.material = "grey";
  d.objects.push_back(ball);
  ObjectDescription box;
  box.shape = ObjectDescription::Shape::box;
  box.box_min = {-1, -1, 2};
  box.box_max = {0, 0.5, 2.5};
  box.material = "grey";
  d.objects.push_back(box);
  const Scene s = build_scene(d);
  const SphereLight& light = s.sphere_lights()[0];
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int clear = 0, maybe = 0;
  for (int i = 0; i < 1500; ++i) {
    // Floor points (y = -1 exactly, as plane hits are projected), points above and below it.
    const Vec3 p{6 * u(rng), i % 3 ? -1.0f : 2.0f * u(rng) + 0.5f, 6 * u(rng)};
    if (!s.light_unoccluded(p, 0)) {
      ++maybe;
      continue;
    }
    ++clear;
    for (int k = 0; k < 64; ++k) {
      // Towards a point inside the light's ball, up to the near side of its sphere (as the
      // light's samples: their rays stop short of the visible cap).
      const Vec3 q = light.center + Vec3{u(rng), u(rng), u(rng)} * (0.57f * light.radius);
      const Vec3 dir = normalize(q - p), oc = p - light.center;
      const float b = dot(oc, dir), c = dot(oc, oc) - light.radius * light.radius;
      const float t = -b - std::sqrt(b * b - c);
      ASSERT_FALSE(s.occluded(Ray{p, dir, t * (1.0f - 1e-4f)})) << i << " " << k;
    }
  }
  EXPECT_GT(clear, 500);
  EXPECT_GT(maybe, 100);
}

TEST(Scene, BuildsFromInMemoryMeshesAndFindsCameraMedium) {
  const Scene s = build_scene(shell_scene());
  EXPECT_EQ(s.statistics().triangles, 2u * 1280u);
  EXPECT_EQ(s.media()[s.camera_medium()].name, "air");
  Hit hit;
  ASSERT_TRUE(s.intersect(Ray{{0, 0, 5}, {0, 0, -1}}, hit));
  EXPECT_NEAR(hit.t, 4.0f, 2e-3f);  // icosphere face centres sit inside the sphere by < 2e-3
  const SurfaceInteraction si = s.interaction(Ray{{0, 0, 5}, {0, 0, -1}}, hit);
  EXPECT_GT(si.ng.z, 0.99f);  // outward
  EXPECT_EQ(s.objects()[si.object].label, "outer");
}

// A floor written with normals that are its faces' normals (S4's floor_200.obj) is shaded flat:
// no normal set, the hit's shading normal is its geometric one exactly. A mesh whose normals
// bend keeps them.
TEST(Scene, MeshWhoseNormalsAreFaceNormalsIsShadedFlat) {
  auto quad = [](Vec3 normal) {
    auto m = std::make_shared<TriangleMesh>();
    m->positions = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    m->triangles = {{0, 1, 2}, {0, 2, 3}};
    m->normals = {normalize(normal)};
    m->normal_indices = {{0, 0, 0}, {0, 0, 0}};
    return m;
  };
  for (const auto& [normal, flat] :
       {std::pair{Vec3{0, 1, 0}, true}, std::pair{Vec3{0, -1, 0}, true},
        std::pair{Vec3{0.01f, 1, 0}, false}}) {
    SceneDescription d;
    d.camera.position = {0, 3, 0.5f};
    d.camera.look_at = {0, 0, 0};
    MaterialDescription grey;
    grey.name = "grey";
    d.materials.push_back(grey);
    ObjectDescription o;
    o.shape = ObjectDescription::Shape::mesh;
    o.mesh = quad(normal);
    o.material = "grey";
    o.label = "floor";
    d.objects.push_back(o);
    const Scene s = build_scene(d);
    EXPECT_EQ(s.objects()[0].normal_set == -1, flat) << normal.x << " " << normal.y;
    const Ray ray{{0.3f, 3, 0.2f}, normalize(Vec3{0.1f, -1, 0.05f})};
    Hit hit;
    ASSERT_TRUE(s.intersect(ray, hit));
    const SurfaceInteraction si = s.interaction(ray, hit);
    if (flat) {
      EXPECT_EQ(si.ns.x, si.ng.x);
      EXPECT_EQ(si.ns.y, si.ng.y);
      EXPECT_EQ(si.ns.z, si.ng.z);
    } else {
      EXPECT_GT(std::abs(si.ns.x), 5e-3f);
    }
  }
}

TEST(Scene, OpenDielectricMeshIsRejected) {
  SceneDescription d = shell_scene();
  auto open = std::make_shared<TriangleMesh>(test::icosphere(2, 0.5f));
  open->triangles.pop_back();
  d.add_dielectric_mesh(open, "water", "ice", "leaky");
  try {
    build_scene(d);
    FAIL();
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("leaky"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("closed"), std::string::npos) << e.what();
    // an in-memory mesh is named once, by its label (not as file and key: "leaky: leaky:")
    EXPECT_EQ(std::string(e.what()).find("leaky: leaky"), std::string::npos) << e.what();
  }
}

TEST(Scene, InwardDielectricMeshIsRejected) {
  SceneDescription d = shell_scene();
  auto inward = std::make_shared<TriangleMesh>(test::icosphere(2, 0.5f));
  for (auto& t : inward->triangles) std::swap(t[1], t[2]);
  d.add_dielectric_mesh(inward, "water", "ice");
  EXPECT_THROW(build_scene(d), UserError);
}

TEST(Scene, UnknownNamesAndMissingFilesAreRejected) {
  SceneDescription d = shell_scene();
  d.objects[1].inside = "juice";
  EXPECT_THROW(build_scene(d), UserError);
  d = shell_scene();
  ObjectDescription o;
  o.shape = ObjectDescription::Shape::mesh;
  o.mesh_file = "/nonexistent/thing.obj";
  o.material = "none";
  d.materials.push_back({});
  d.materials.back().name = "none";
  d.objects.push_back(o);
  EXPECT_THROW(build_scene(d), UserError);
}

TEST(Scene, AmbiguousCameraMediumMustBeGiven) {
  SceneDescription d = shell_scene();
  d.add_dielectric_mesh(std::make_shared<TriangleMesh>(test::icosphere(1, 0.2f, {3, 0, 0})),
                        "water", "vacuum");
  EXPECT_THROW(build_scene(d), UserError);
  d.camera.medium = "air";
  EXPECT_NO_THROW(build_scene(d));
}

TEST(Scene, PackedTriangleLeavesMatchBruteForce) {
  // Scene::intersect tests BVH leaves four triangles at a time (triangle4.h); it must find exactly
  // what the scalar watertight test finds over all triangles, for 10^5 random rays.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), s(-0.2f, 0.2f);
  auto soup = std::make_shared<TriangleMesh>();
  for (std::uint32_t i = 0; i < 600; ++i) {
    const Vec3 c{u(rng), u(rng), u(rng)};
    for (int k = 0; k < 3; ++k) soup->positions.push_back(c + Vec3{s(rng), s(rng), s(rng)});
    soup->triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
  }
  SceneDescription d;
  d.materials.push_back({});
  d.materials.back().name = "grey";
  ObjectDescription o;
  o.shape = ObjectDescription::Shape::mesh;
  o.mesh = soup;
  o.material = "grey";
  d.objects.push_back(o);
  const Scene scene = build_scene(d);
  std::vector<std::array<Vec3, 3>> all;
  for (const Primitive& p : scene.primitives()) all.push_back({p.a, p.b, p.c});
  int mismatches = 0, hits = 0;
  for (int i = 0; i < 100000; ++i) {
    Ray r{{1.5f * u(rng), 1.5f * u(rng), 1.5f * u(rng)}, normalize(Vec3{u(rng), u(rng), u(rng)})};
    if (i % 4 == 0) r.t_max = std::abs(u(rng));
    const ShearedRay sr(r);
    float best = r.t_max;
    bool brute = false;
    for (const auto& t : all) {
      TriangleHit h;
      if (intersect_triangle(sr, t[0], t[1], t[2], best, h)) {
        best = h.t;
        brute = true;
      }
    }
    Hit hit;
    const bool found = scene.intersect(r, hit);
    if (found != brute || (found && hit.t != best)) ++mismatches;
    if (scene.occluded(r) != brute) ++mismatches;
    hits += brute;
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(hits, 10000);
}

TEST(Scene, CoordinatesBeyondFloatAreRejected) {
  SceneDescription d = shell_scene();
  ObjectDescription o;
  o.shape = ObjectDescription::Shape::sphere;
  o.radius = 1e39;  // finite in double, infinite in float
  o.inside = "water";
  o.outside = "air";
  d.objects.push_back(o);
  EXPECT_THROW(build_scene(d), UserError);
  d = shell_scene();
  d.objects[0].scale = 1e39;  // the mesh's vertices overflow after the transform
  EXPECT_THROW(build_scene(d), UserError);
}

TEST(Scene, BadImageSizeIsRejected) {
  SceneDescription d = shell_scene();
  d.image.width = 0;
  EXPECT_THROW(build_scene(d), UserError);
}

}  // namespace
}  // namespace thaw::render

namespace thaw::render {
namespace {

/// The shell scene with an opaque ball and box, and one light.
SceneDescription scene_with_light(LightDescription light) {
  SceneDescription d = shell_scene();
  MaterialDescription m;
  m.name = "grey";
  d.materials.push_back(m);
  ObjectDescription ball;
  ball.label = "ball";
  ball.shape = ObjectDescription::Shape::sphere;
  ball.center = {3, 0, 0};
  ball.radius = 1;
  ball.material = "grey";
  d.objects.push_back(ball);
  ObjectDescription box;
  box.label = "crate";
  box.shape = ObjectDescription::Shape::box;
  box.box_min = {-4, -1, -1};
  box.box_max = {-3, 1, 1};
  box.material = "grey";
  d.objects.push_back(box);
  d.lights.push_back(light);
  return d;
}

LightDescription sphere_light(Vec3d c, double r) {
  LightDescription l;
  l.kind = LightDescription::Kind::sphere;
  l.position = c;
  l.radius = r;
  l.intensity = 2.0;
  return l;
}

std::string build_error(const SceneDescription& d) {
  try {
    build_scene(d);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(Scene, SphereLightIsAVisibleEmitterOfRadianceIOverPiR2) {
  const Scene s = build_scene(scene_with_light(sphere_light({0, 5, 0}, 0.5)));
  ASSERT_EQ(s.sphere_lights().size(), 1u);
  EXPECT_TRUE(s.lights().empty());
  const float L = float(2.0 / (3.14159265358979323846 * 0.25));
  EXPECT_FLOAT_EQ(s.sphere_lights()[0].radiance.g, L);
  // A ray straight up from the origin's top meets the light's sphere at y = 4.5, emissive, L.
  Hit hit;
  ASSERT_TRUE(s.intersect(Ray{{0, 2, 0}, {0, 1, 0}}, hit));
  EXPECT_NEAR(hit.t, 2.5f, 1e-5f);
  const SceneObject& obj = s.objects()[s.interaction(Ray{{0, 2, 0}, {0, 1, 0}}, hit).object];
  EXPECT_EQ(obj.label, "lights[0]");
  ASSERT_FALSE(obj.dielectric);
  EXPECT_EQ(s.materials()[obj.material].kind, Material::Kind::emissive);
  EXPECT_FLOAT_EQ(s.materials()[obj.material].emission.r, L);
}

TEST(Scene, LightsInsideOrCuttingObjectsAreRejected) {
  LightDescription point;
  point.position = {3, 0.5, 0};
  EXPECT_NE(build_error(scene_with_light(point)).find("lights[0].position"), std::string::npos);
  EXPECT_NE(build_error(scene_with_light(point)).find("inside opaque object 'ball'"),
            std::string::npos);
  point.position = {-3.5, 0, 0};
  EXPECT_NE(build_error(scene_with_light(point)).find("inside opaque object 'crate'"),
            std::string::npos);
  EXPECT_NE(build_error(scene_with_light(sphere_light({3, 0.2, 0}, 0.1))).find("inside opaque"),
            std::string::npos);
  // Cutting the ball's surface, the crate's, or the ice shell's (a dielectric sphere).
  EXPECT_NE(build_error(scene_with_light(sphere_light({3, 1.5, 0}, 0.6))).find("lights[0].radius"),
            std::string::npos);
  EXPECT_NE(build_error(scene_with_light(sphere_light({-2.8, 0, 0}, 0.3))).find("'crate'"),
            std::string::npos);
  EXPECT_NE(build_error(scene_with_light(sphere_light({2.1, 0, 0}, 0.3))).find("'ball'"),
            std::string::npos);
  // Clear of everything: fine, and a point light outside the objects is too.
  EXPECT_EQ(build_error(scene_with_light(sphere_light({0, 3, 0}, 0.5))), "");
  point.position = {0, 3, 0};
  EXPECT_EQ(build_error(scene_with_light(point)), "");
  // Inside a box room (or dome) that the camera shares: fine.
  SceneDescription room = scene_with_light(point);
  ObjectDescription walls;
  walls.shape = ObjectDescription::Shape::box;
  walls.box_min = {-50, -50, -50};
  walls.box_max = {50, 50, 50};
  walls.material = "grey";
  room.objects.push_back(walls);
  EXPECT_EQ(build_error(room), "");
  room.camera.position = {0, 0, 60};
  EXPECT_NE(build_error(room).find("inside opaque object 'objects[4]' (and the camera is not)"),
            std::string::npos)
      << build_error(room);
}

}  // namespace
}  // namespace thaw::render
