// The glTF loader on the shared scenes and on hand-made files, good and bad. Every bad file must
// give one error naming the file and what is wrong, and leave the output untouched.
#include "scene/gltf_loader.h"

#include "corpus.h"
#include "gltf_fixture.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include <fcntl.h>
#include <unistd.h>

namespace {
namespace fs = std::filesystem;
using nlohmann::json;

TEST_F(GltfLoader, SharedScenesLoadWithTheirTriangleCounts) {
  const std::pair<const char*, size_t> scenes[] = {{"stanford-bunny.glb", 69451},
                                                   {"armadillo.glb", 50000},
                                                   {"spot.glb", 5856},
                                                   {"fandisk.glb", 12946},
                                                   {"teapot-no-normals.glb", 6320}};
  for (const auto& [file, triangles] : scenes) {
    ASSERT_TRUE(fs::exists(kShared / "scenes" / file)) << "the shared scenes must be beside the repository: " << kShared;
    const scene::Scene loaded = load_ok(kShared / "scenes" / file);
    EXPECT_EQ(loaded.triangle_count(), triangles) << file;
    EXPECT_GT(loaded.bounds.radius(), 0.0) << file;
    for (const scene::Mesh& mesh : loaded.meshes)
      for (const scene::Vertex& v : mesh.vertices) ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-4f) << file;
  }
}

TEST_F(GltfLoader, MissingNormalsBecomeFlatNormals) {
  const scene::Scene teapot = load_ok(kShared / "scenes" / "teapot-no-normals.glb");
  size_t checked = 0;
  for (const scene::Mesh& mesh : teapot.meshes)
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const scene::Vertex& a = mesh.vertices[mesh.indices[t]];
      const scene::Vertex& b = mesh.vertices[mesh.indices[t + 1]];
      const scene::Vertex& c = mesh.vertices[mesh.indices[t + 2]];
      const glm::dvec3 face = glm::cross(glm::dvec3(b.position - a.position), glm::dvec3(c.position - a.position));
      if (glm::length(face) < 1e-12) continue;  // degenerate triangles keep a zero normal
      const glm::dvec3 expected = glm::normalize(face);
      for (const scene::Vertex* v : {&a, &b, &c}) EXPECT_NEAR(glm::dot(glm::dvec3(v->normal), expected), 1.0, 1e-5);
      ++checked;
    }
  EXPECT_GT(checked, 6000u);
}

TEST_F(GltfLoader, LoadsATriangleWithNodeTransforms) {
  json doc = triangle();
  doc["nodes"] = {{{"children", {1}}, {"translation", {10, 0, 0}}}, {{"mesh", 0}, {"scale", {2, 2, 2}}}};
  const scene::Scene loaded = load_ok(write(doc));
  ASSERT_EQ(loaded.instances.size(), 1u);
  EXPECT_NEAR(loaded.bounds.min.x, 10.0, 1e-12);
  EXPECT_NEAR(loaded.bounds.max.x, 12.0, 1e-12);
  EXPECT_NEAR(loaded.bounds.max.y, 2.0, 1e-12);
}

// A node's rotation is the unit quaternion written (x, y, z, w) (glTF 2.0, node.rotation), applied
// after its scale and before its translation, and a child's transform inside its parent's: a model
// with turned nodes stands as its author turned it. The expected points are worked out by hand.
TEST_F(GltfLoader, ANodesRotationIsTheQuaternionXyzwBetweenItsScaleAndItsTranslation) {
  const double s = std::sqrt(0.5);
  struct Case {
    const char* what;
    json nodes;
    std::vector<glm::dvec3> expected;  // where the triangle's corners (0,0,0), (1,0,0), (0,1,0) land
  };
  const Case cases[] = {
      {"a quarter turn about +Y, doubled and moved along +X",
       {{{"mesh", 0}, {"rotation", {0, s, 0, s}}, {"scale", {2, 2, 2}}, {"translation", {10, 0, 0}}}},
       {{10, 0, 0}, {10, 0, -2}, {10, 2, 0}}},
      {"a quarter turn about +X", {{{"mesh", 0}, {"rotation", {s, 0, 0, s}}}}, {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}},
      {"a child moved along +X inside a parent turned a quarter about +Z",
       {{{"children", {1}}, {"rotation", {0, 0, s, s}}}, {{"mesh", 0}, {"translation", {1, 0, 0}}}},
       {{0, 1, 0}, {0, 2, 0}, {-1, 1, 0}}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    json doc = triangle();
    doc["nodes"] = c.nodes;
    doc["scenes"] = {{{"nodes", {0}}}};
    const scene::Scene loaded = load_ok(write(doc));
    ASSERT_EQ(loaded.instances.size(), 1u);
    const scene::Instance& instance = loaded.instances[0];
    const scene::Mesh& mesh = loaded.meshes.at(static_cast<size_t>(instance.mesh));
    std::vector<bool> found(c.expected.size(), false);
    for (const scene::Vertex& v : mesh.vertices) {
      const glm::dvec3 world(instance.world * glm::dvec4(glm::dvec3(v.position), 1.0));
      bool matched = false;
      for (size_t k = 0; k < c.expected.size(); ++k)
        if (glm::length(world - c.expected[k]) < 1e-6) matched = found[k] = true;
      EXPECT_TRUE(matched) << "a corner at (" << world.x << ", " << world.y << ", " << world.z << ")";
    }
    for (size_t k = 0; k < found.size(); ++k) EXPECT_TRUE(found[k]) << "no corner at expected point " << k;
  }
}

// The source vertex of every output index. Without NORMAL the loader gives each triangle its own
// vertices (flat normals), so the vertex is told by its position: vertex v of vertex_row() lies at x = v.
std::vector<uint32_t> source_vertices(const scene::Mesh& mesh) {
  std::vector<uint32_t> out;
  for (uint32_t index : mesh.indices) out.push_back(static_cast<uint32_t>(std::lround(mesh.vertices.at(index).position.x)));
  return out;
}

// m vertices with x = v, none three in a line (y = v^2 / 10), so every triangle has a normal.
std::vector<float> vertex_row(int m) {
  std::vector<float> positions;
  for (int v = 0; v < m; ++v) positions.insert(positions.end(), {float(v), 0.1f * float(v * v), 0.0f});
  return positions;
}

// glTF 2.0, 3.7.2.1 (Topology Types): triangle p_i of a strip is {v_i, v_(i + (1 + i % 2)), v_(i + (2 - i % 2))},
// of a fan {v_(i + 1), v_(i + 2), v_0}, for 0 <= i < count - 2; v_k is the k-th index (or vertex).
std::vector<uint32_t> spec_triangles(int mode, const std::vector<uint32_t>& v) {
  std::vector<uint32_t> out;
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    if (mode == 5)
      out.insert(out.end(), {v[i], v[i + (1 + i % 2)], v[i + (2 - i % 2)]});
    else
      out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
  }
  return out;
}

TEST_F(GltfLoader, StripsAndFansBecomeTheTrianglesTheSpecDefines) {
  for (int mode : {5, 6})
    for (int m : {3, 4, 5, 6, 8, 9}) {
      // Indexed, through a permutation (gcd(7, m) = 1), so the rule must act on indices, not vertices.
      std::vector<uint16_t> indices;
      std::vector<uint32_t> v;
      for (int i = 0; i < m; ++i) {
        indices.push_back(static_cast<uint16_t>((7 * i + 3) % m));
        v.push_back(indices.back());
      }
      json doc = triangle(vertex_row(m), indices);
      doc["meshes"][0]["primitives"][0]["mode"] = mode;
      const scene::Scene indexed = load_ok(write(doc));
      ASSERT_EQ(indexed.meshes.size(), 1u) << "mode " << mode << ", " << m << " indices";
      EXPECT_EQ(source_vertices(indexed.meshes[0]), spec_triangles(mode, v)) << "mode " << mode << ", " << m << " indices";
    }
  for (int mode : {5, 6})
    for (int m : {3, 4, 5, 6, 7}) {
      json doc = triangle(vertex_row(m));
      doc["meshes"][0]["primitives"][0]["mode"] = mode;
      doc["meshes"][0]["primitives"][0].erase("indices");
      std::vector<uint32_t> v;
      for (int i = 0; i < m; ++i) v.push_back(static_cast<uint32_t>(i));
      const scene::Scene plain = load_ok(write(doc));
      ASSERT_EQ(plain.meshes.size(), 1u) << "mode " << mode << ", " << m << " vertices";
      EXPECT_EQ(source_vertices(plain.meshes[0]), spec_triangles(mode, v)) << "mode " << mode << ", " << m << " vertices";
    }
  // A unit square as a strip and as a fan: both its triangles face +Z, as the spec's order promises.
  for (int mode : {5, 6}) {
    json doc = mode == 5 ? triangle({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, {0, 1, 2, 3})
                         : triangle({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 3});
    doc["meshes"][0]["primitives"][0]["mode"] = mode;
    const scene::Scene loaded = load_ok(write(doc));
    const scene::Mesh& mesh = loaded.meshes.at(0);
    ASSERT_EQ(mesh.indices.size(), 6u) << "mode " << mode;
    for (size_t t = 0; t < 6; t += 3) {
      const glm::vec3 a = mesh.vertices[mesh.indices[t]].position, b = mesh.vertices[mesh.indices[t + 1]].position,
                      c = mesh.vertices[mesh.indices[t + 2]].position;
      EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "mode " << mode << " triangle " << t / 3;
    }
  }
}

TEST_F(GltfLoader, TriangleListsKeepTheirIndicesAndDropAnIncompleteLastTriangle) {
  // The spec requires a multiple of 3; the loader keeps the whole triangles and drops the rest.
  const std::vector<uint16_t> indices = {4, 0, 2, 1, 3, 5, 6};
  const scene::Scene loaded = load_ok(write(triangle(vertex_row(7), indices)));
  EXPECT_EQ(source_vertices(loaded.meshes.at(0)), (std::vector<uint32_t>{4, 0, 2, 1, 3, 5}));
}

TEST_F(GltfLoader, PointsAndLinesAreSkippedWithAWarningNamingThePrimitive) {
  // Modes 0..3 (POINTS, LINES, LINE_LOOP, LINE_STRIP) have no triangles to shade: the primitive is
  // dropped and named in a warning, and the file's triangles still load.
  for (int mode : {0, 1, 2, 3}) {
    json doc = triangle(vertex_row(4), {0, 1, 2, 1, 3, 2});
    json lines = doc["meshes"][0]["primitives"][0];
    lines["mode"] = mode;
    doc["meshes"][0]["primitives"].push_back(lines);
    scene::Scene out;
    scene::LoadReport report;
    ASSERT_TRUE(scene::load_gltf(write(doc), out, report)) << report.error;
    ASSERT_EQ(out.meshes.size(), 1u) << "mode " << mode;
    EXPECT_EQ(source_vertices(out.meshes[0]), (std::vector<uint32_t>{0, 1, 2, 1, 3, 2})) << "mode " << mode;
    ASSERT_EQ(report.warnings.size(), 1u) << "mode " << mode;
    EXPECT_EQ(report.warnings[0], "meshes[0].primitives[1]: mode " + std::to_string(mode) + " is not triangles; skipped");
  }
}

TEST_F(GltfLoader, AcceptsByteAndIntIndicesAndNonIndexedPrimitives) {
  // Without NORMAL the triangles are unshared (flat normals), so the order of the output vertices
  // tells which indices were read.
  auto corner_order = [&](const json& doc) {
    const scene::Scene loaded = load_ok(write(doc));
    std::vector<glm::vec3> order;
    for (uint32_t index : loaded.meshes.at(0).indices) order.push_back(loaded.meshes[0].vertices[index].position);
    return order;
  };
  const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  json doc = triangle();
  std::vector<unsigned char> bytes;
  append<float>(bytes, {0, 0, 0, 1, 0, 0, 0, 1, 0});
  append<uint32_t>(bytes, {1, 2, 0});
  append<uint8_t>(bytes, {2, 0, 1, 0});
  doc["buffers"][0] = {{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}};
  doc["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
                        {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 12}},
                        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 3}}};
  doc["accessors"][1] = {{"bufferView", 1}, {"componentType", 5125}, {"count", 3}, {"type", "SCALAR"}};
  doc["accessors"].push_back({{"bufferView", 2}, {"componentType", 5121}, {"count", 3}, {"type", "SCALAR"}});
  EXPECT_EQ(corner_order(doc), (std::vector<glm::vec3>{b, c, a}));
  doc["meshes"][0]["primitives"][0]["indices"] = 2;
  EXPECT_EQ(corner_order(doc), (std::vector<glm::vec3>{c, a, b}));
  doc["meshes"][0]["primitives"][0].erase("indices");
  EXPECT_EQ(corner_order(doc), (std::vector<glm::vec3>{a, b, c}));
}

TEST_F(GltfLoader, LoadsABaseColorTextureThroughOpenImageIO) {
  const fs::path png = dir_ / "scene" / "albedo.png";
  const unsigned char pixels[2 * 2 * 3] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
  auto output = OIIO::ImageOutput::create(png.string());
  ASSERT_TRUE(output);
  ASSERT_TRUE(output->open(png.string(), OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(output->write_image(OIIO::TypeDesc::UINT8, pixels));
  output->close();
  json doc = triangle();
  doc["images"] = {{{"uri", "albedo.png"}}};
  doc["textures"] = {{{"source", 0}}};
  doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"baseColorFactor", {1, 0.5, 1, 1}}}}}};
  doc["meshes"][0]["primitives"][0]["material"] = 0;
  const scene::Scene loaded = load_ok(write(doc));
  ASSERT_EQ(loaded.textures.size(), 1u);
  EXPECT_EQ(loaded.textures[0].width, 2);
  EXPECT_EQ(loaded.textures[0].rgba, (std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255}));
  const scene::Material& material = loaded.materials.at(static_cast<size_t>(loaded.meshes[0].material));
  EXPECT_EQ(material.base_color_texture, 0);
  EXPECT_FLOAT_EQ(material.base_color.g, 0.5f);
}

TEST_F(GltfLoader, TruncatedBinaryFileIsAClearError) {
  std::ifstream in(kShared / "scenes" / "spot.glb", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1000u);
  const fs::path path = dir_ / "scene" / "truncated.glb";
  std::ofstream(path, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const std::string error = error_of(path);
  EXPECT_NE(error.find(": not a valid glTF 2.0 file: GLB header length " + std::to_string(bytes.size()) + " exceeds the file's " +
                       std::to_string(bytes.size() / 2) + " bytes (the file is truncated)"),
            std::string::npos)
      << error;
}

// glTF-Validator warns about bytes after the GLB's declared length (GLB_EXTRA_DATA) and calls the
// file valid: it loads, with a warning naming how many bytes were ignored.
TEST_F(GltfLoader, BytesAfterTheDeclaredGlbLengthAreIgnoredWithAWarning) {
  std::ifstream in(kShared / "scenes" / "spot.glb", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const fs::path path = dir_ / "scene" / "trailing.glb";
  std::ofstream(path, std::ios::binary) << bytes << "xyz";
  scene::Scene scene;
  scene::LoadReport report;
  ASSERT_TRUE(scene::load_gltf(path, scene, report)) << report.error;
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_EQ(report.warnings[0], "GLB: 3 bytes after the declared length " + std::to_string(bytes.size()) + "; ignored");
  EXPECT_GT(scene.triangle_count(), 1000u);
}

TEST_F(GltfLoader, NotJsonAtAllIsAClearError) {
  const fs::path path = dir_ / "scene" / "garbage.gltf";
  std::ofstream(path) << "{ this is not json";
  EXPECT_NE(error_of(path).find("not a valid glTF"), std::string::npos);
}

TEST_F(GltfLoader, NonFinitePositionsAreRejected) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    const std::string error = error_of(write(triangle({0, 0, 0, 1, bad, 0, 0, 1, 0})));
    EXPECT_NE(error.find("attributes.POSITION"), std::string::npos) << error;
    EXPECT_NE(error.find("expected a finite number"), std::string::npos) << error;
  }
}

TEST_F(GltfLoader, OutOfRangeIndicesAreRejected) {
  const std::string error = error_of(write(triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 7})));
  EXPECT_NE(error.find("indices: element 2 is 7, expected less than the vertex count 3"), std::string::npos) << error;
  // At the bound: the vertex count itself is one too many, one less is the last vertex.
  const std::string at_bound = error_of(write(triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {3, 1, 2})));
  EXPECT_NE(at_bound.find("indices: element 0 is 3, expected less than the vertex count 3"), std::string::npos) << at_bound;
  EXPECT_EQ(load_ok(write(triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {2, 1, 0}))).triangle_count(), 1u);
}

TEST_F(GltfLoader, AccessorBoundsAreCheckedAtTheirLastByte) {
  // triangle() fits its views exactly (36 bytes of positions, 6 of indices), so it loads; one more
  // element or a 4-byte offset needs 48 or 40 bytes, and an accessor index equal to their count is out.
  EXPECT_EQ(load_ok(write(triangle())).triangle_count(), 1u);
  json doc = triangle();
  doc["accessors"][0]["count"] = 4;
  std::string error = error_of(write(doc));
  EXPECT_NE(error.find("attributes.POSITION (accessors[0]): needs 48 bytes but its buffer view has 36"), std::string::npos)
      << error;
  doc = triangle();
  doc["accessors"][0]["byteOffset"] = 4;
  error = error_of(write(doc));
  EXPECT_NE(error.find("needs 40 bytes but its buffer view has 36"), std::string::npos) << error;
  doc = triangle();
  doc["accessors"][1]["count"] = 4;
  error = error_of(write(doc));
  EXPECT_NE(error.find("indices (accessors[1]): needs 8 bytes but its buffer view has 6"), std::string::npos) << error;
  doc = triangle();
  doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 2;
  error = error_of(write(doc));
  EXPECT_NE(error.find("attributes.POSITION: 2 is out of range; expected an index into accessors (there are 2)"),
            std::string::npos)
      << error;
}

TEST_F(GltfLoader, AccessorsBeyondTheirBufferViewAreRejected) {
  json doc = triangle();
  doc["accessors"][0]["count"] = 100;
  const std::string error = error_of(write(doc));
  EXPECT_NE(error.find("needs 1200 bytes but its buffer view has 36"), std::string::npos) << error;
  doc = triangle();
  doc["bufferViews"][0]["byteLength"] = 100000;
  EXPECT_NE(error_of(write(doc)).find("bufferViews[0]: bytes 0..100000 lie beyond buffers[0].byteLength 44"), std::string::npos);
  doc = triangle();
  doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
  EXPECT_NE(error_of(write(doc)).find("POSITION: 9 is out of range; expected an index into accessors"), std::string::npos);
}

TEST_F(GltfLoader, MissingBufferFileIsAClearError) {
  json doc = triangle();
  doc["buffers"][0]["uri"] = "missing.bin";
  const std::string error = error_of(write(doc));
  EXPECT_NE(error.find("missing.bin"), std::string::npos) << error;
}

TEST_F(GltfLoader, UrisMayNotEscapeTheScenesFolder) {
  std::ofstream(dir_ / "secret.bin") << std::string(48, 'x');
  json doc = triangle();
  doc["buffers"][0]["uri"] = "../secret.bin";
  std::string error = error_of(write(doc));
  EXPECT_NE(error.find("buffers[0].uri: '../secret.bin' escapes the scene's folder"), std::string::npos) << error;
  doc["buffers"][0]["uri"] = "sub/../../secret.bin";
  EXPECT_NE(error_of(write(doc)).find("escapes the scene's folder"), std::string::npos);
  doc["buffers"][0]["uri"] = (dir_ / "secret.bin").string();
  EXPECT_NE(error_of(write(doc)).find("is an absolute path"), std::string::npos);
  doc["buffers"][0]["uri"] = "file:///etc/passwd";
  EXPECT_NE(error_of(write(doc)).find("is a URL"), std::string::npos);
  // A symbolic link inside the folder that points outside is caught when the file is opened.
  fs::create_symlink(dir_ / "secret.bin", dir_ / "scene" / "link.bin");
  doc["buffers"][0]["uri"] = "link.bin";
  const std::string link_error = error_of(write(doc));
  EXPECT_NE(link_error.find("outside the scene's folder"), std::string::npos) << link_error;
}

TEST_F(GltfLoader, EmptyScenesAreRejected) {
  json doc = triangle();
  doc["scenes"] = json::array({json{{"nodes", json::array()}}});
  EXPECT_NE(error_of(write(doc)).find("no scene with nodes"), std::string::npos);
  doc = triangle();
  doc["nodes"] = {json::object()};
  EXPECT_NE(error_of(write(doc)).find("no triangles"), std::string::npos);
  doc = triangle();
  doc["meshes"][0]["primitives"][0]["mode"] = 0;  // points only
  EXPECT_NE(error_of(write(doc)).find("no triangles"), std::string::npos);
}

TEST_F(GltfLoader, NodeCyclesAndSharedChildrenAreRejected) {
  json doc = triangle();
  doc["nodes"] = {{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}};
  EXPECT_NE(error_of(write(doc)).find("cycle"), std::string::npos);
  doc["nodes"] = {{{"children", {2}}}, {{"children", {2}}}, {{"mesh", 0}}};
  doc["scenes"][0]["nodes"] = {0, 1};
  EXPECT_NE(error_of(write(doc)).find("more than one parent"), std::string::npos);
}

TEST_F(GltfLoader, UnsupportedRequiredExtensionsAreRejected) {
  json doc = triangle();
  doc["extensionsUsed"] = {"KHR_texture_basisu"};
  doc["extensionsRequired"] = {"KHR_texture_basisu"};
  EXPECT_NE(error_of(write(doc)).find("extensionsRequired: 'KHR_texture_basisu' is not supported"), std::string::npos);
}

TEST_F(GltfLoader, OverflowingTransformsAndWrongFileTypesAreRejected) {
  // Finite in JSON, but the world bounds overflow to infinity once the scale is applied.
  json doc = triangle();
  doc["nodes"][0]["scale"] = {1e308, 1e308, 1e308};
  doc["nodes"] = {{{"children", {1}}, {"scale", {1e308, 1e308, 1e308}}}, {{"mesh", 0}, {"scale", {1e308, 1, 1}}}};
  EXPECT_NE(error_of(write(doc)).find("bounds are not finite"), std::string::npos);
  std::ofstream(dir_ / "scene" / "model.obj") << "v 0 0 0\n";
  EXPECT_NE(error_of(dir_ / "scene" / "model.obj").find("expected a .gltf or .glb file"), std::string::npos);
  EXPECT_NE(error_of(dir_ / "scene" / "absent.glb").find("no such file"), std::string::npos);
}

// --- The corpus (tests/gltf_corpus): one test per file, each with its exact verdict --------------

struct Verdict {
  std::string error;                       // empty: the file loads
  std::vector<std::string> warnings = {};  // when it loads
};

const std::string kDrawnWhite = "; its texture is drawn white";
const std::string kSafe = "9007199254740991";  // 2^53 - 1, the largest integer JSON keeps exactly

// Why each verdict is what it is, where it is not plain "glTF says it is an error, and it concerns
// data the player reads":
// - points-only, no-scenes, empty-scene: valid glTF, but nothing to show; a kiosk refuses with a
//   line saying so rather than playing a black screen (lines and points next to triangles load,
//   with a warning).
// - utf8-bom: the spec forbids the BOM but lets readers ignore it; ignored with a warning.
// - texture-*: a texture that cannot be used is drawn white with a warning; the geometry still plays.
const std::map<std::string, Verdict> kVerdicts = {
    {"valid-triangle.gltf", {}},
    {"valid-triangle.glb", {}},
    {"valid-no-indices.gltf", {}},
    {"valid-u8-indices.gltf", {}},
    {"valid-u32-indices.gltf", {}},
    {"valid-triangle-strip.gltf", {}},
    {"valid-triangle-fan.gltf", {}},
    {"valid-normals.gltf", {}},
    {"valid-texcoords.gltf", {}},
    {"valid-texcoords-normalized-ushort.gltf", {}},
    {"valid-interleaved-stride-24.gltf", {}},
    {"valid-stride-252.gltf", {}},
    {"valid-texture-png-rgb.gltf", {}},
    {"valid-texture-png-grey.gltf", {}},
    {"valid-texture-png-rgba.gltf", {}},
    {"valid-texture-jpeg.gltf", {}},
    {"valid-image-in-bufferview.glb", {}},
    {"valid-node-trs.gltf", {}},
    {"valid-node-matrix.gltf", {}},
    {"valid-two-scenes.gltf", {}},
    {"valid-lines-and-triangles.gltf", {"", {"meshes[0].primitives[1]: mode 1 is not triangles; skipped"}}},
    {"valid-version-2.1.gltf", {}},
    {"valid-min-version-2.0.gltf", {}},
    {"valid-morph-target.gltf", {}},
    {"valid-glb-json-chunk-only.glb", {}},
    {"valid-extras-nested-100.gltf", {}},
    {"valid-unicode-names.gltf", {}},
    {"valid-node-chain-100000.gltf", {}},
    {"valid-5000-nodes-share-a-mesh.gltf", {}},
    {"valid-two-primitives.gltf", {}},
    {"valid-camera-node.gltf", {}},
    {"valid-extensions-used.gltf", {}},
    {"valid-glb-unknown-chunk.glb", {"", {"GLB chunk 2 at byte 556: unknown chunk type 0x5458454E; ignored"}}},
    {"points-only.gltf", {"meshes: the scene contains no triangles to render"}},
    {"no-scenes.gltf", {"scenes: the file has no scene with nodes to show"}},
    {"empty-scene.gltf", {"scenes: the file has no scene with nodes to show"}},
    {"empty.glb", {"not a valid glTF 2.0 file: the file is empty (0 bytes); expected glTF 2.0 binary"}},
    {"negative-byteoffset.gltf", {"bufferViews[0].byteOffset: -4 is out of range; expected an integer from 0 to " + kSafe}},
    {"version-1.0.gltf", {"asset.version: \"1.0\" is not glTF 2; expected \"2.0\" (or another 2.x)"}},
    {"min-version-2.1.gltf", {"asset.minVersion: \"2.1\" asks for more than this player reads; expected \"2.0\""}},
    {"version-missing.gltf", {"asset.version: missing; expected \"2.0\""}},
    {"json-nested-200000.gltf",
     {"not a valid glTF 2.0 file: JSON nests deeper than 512 levels at byte 1107; expected at most 512"}},
    {"json-nested-200000.glb",
     {"not a valid glTF 2.0 file: JSON nests deeper than 512 levels at byte 1107; expected at most 512"}},
    {"utf8-bom.gltf", {"", {"the JSON starts with a UTF-8 byte-order mark, which glTF forbids; ignored"}}},
    {"stride-below-element.gltf",
     {"meshes[0].primitives[0].attributes.POSITION (accessors[0]): bufferViews[0].byteStride 8 is smaller than an "
      "element of 12 bytes"}},
    {"stride-above-252.gltf", {"bufferViews[0].byteStride: 256 is out of range; expected an integer from 4 to 252"}},
    {"stride-not-multiple-of-4.gltf", {"bufferViews[0].byteStride: 14 is not a multiple of 4; expected 4, 8, .. 252"}},
    {"position-type-vec2.gltf",
     {"meshes[0].primitives[0].attributes.POSITION (accessors[0]): expected 3 components per element, got 2"}},
    {"position-componenttype-ushort.gltf",
     {"meshes[0].primitives[0].attributes.POSITION (accessors[0]): unsigned short is not allowed here; expected float"}},
    {"indices-type-vec2.gltf", {"meshes[0].primitives[0].indices (accessors[1]): expected 1 components per element, got 2"}},
    {"indices-float.gltf",
     {"meshes[0].primitives[0].indices (accessors[2]): float is not allowed here; expected one of unsigned byte, "
      "unsigned short, unsigned int"}},
    {"attribute-counts-differ.gltf", {"meshes[0].primitives[0].attributes.TEXCOORD_0: count 2 differs from POSITION's 3"}},
    {"unread-attribute-count-differs.gltf", {"meshes[0].primitives[0].attributes.COLOR_0: count 2 differs from POSITION's 3"}},
    {"count-beyond-2^64.gltf",
     {"accessors[0].count: 1.8446744073709552e+19 is not an integer; expected an integer from 1 to " + kSafe}},
    {"accessor-offset-beyond-2^64.gltf",
     {"accessors[0].byteOffset: 3.6893488147419103e+19 is not an integer; expected an integer from 0 to " + kSafe}},
    {"bufferview-offset-beyond-2^64.gltf",
     {"bufferViews[0].byteOffset: 1.8446744073709552e+19 is not an integer; expected an integer from 0 to " + kSafe}},
    {"count-times-size-overflows.gltf",
     {"accessors[0].count: 4611686018427387904 is out of range; expected an integer from 1 to " + kSafe}},
    {"count-above-limit.gltf",
     {"meshes[0].primitives[0].attributes.POSITION (accessors[0]): count 1099511627776 exceeds the limit of 268435456 "
      "elements"}},
    {"count-float.gltf", {"accessors[0].count: 3.5 is not an integer; expected an integer from 1 to " + kSafe}},
    {"count-string.gltf", {"accessors[0].count: \"3\" is not an integer; expected an integer from 1 to " + kSafe}},
    {"count-zero.gltf", {"accessors[0].count: 0 is out of range; expected an integer from 1 to " + kSafe}},
    {"accessor-beyond-bufferview.gltf",
     {"meshes[0].primitives[0].attributes.POSITION (accessors[0]): needs 48 bytes but its buffer view has 36"}},
    {"bufferview-beyond-buffer.gltf", {"bufferViews[0]: bytes 0..1000 lie beyond buffers[0].byteLength 44"}},
    {"accessor-unaligned.gltf",
     {"meshes[0].primitives[0].attributes.POSITION (accessors[0]): starts at byte 2 of its buffer; expected a multiple "
      "of the component size 4"}},
    {"index-beyond-vertex-count.gltf",
     {"meshes[0].primitives[0].indices: element 2 is 7, expected less than the vertex count 3"}},
    {"position-nan.gltf",
     {"meshes[0].primitives[0].attributes.POSITION: element 1 component 1 is nan, expected a finite number"}},
    {"accessor-index-out-of-range.gltf",
     {"meshes[0].primitives[0].attributes.POSITION: 9 is out of range; expected an index into accessors (there are 2)"}},
    {"sparse-indices-out-of-range.gltf",
     {"meshes[0].primitives[0].attributes.POSITION (accessors[0]).sparse.indices: element 0 is 7; expected strictly "
      "increasing indices below the accessor's count 3"}},
    {"morph-target-counts-differ.gltf", {"meshes[0].primitives[0].targets[0].POSITION: count 2 differs from POSITION's 3"}},
    {"mode-out-of-range.gltf", {"meshes[0].primitives[0].mode: 7 is out of range; expected an integer from 0 to 6"}},
    {"scene-out-of-range.gltf", {"scene: 5 is out of range; expected an index into scenes (there are 1)"}},
    {"scene-node-out-of-range.gltf", {"scenes[0].nodes[0]: 3 is out of range; expected an index into nodes (there are 1)"}},
    {"node-mesh-out-of-range.gltf", {"nodes[0].mesh: 2 is out of range; expected an index into meshes (there are 1)"}},
    {"sampler-out-of-range.gltf", {"textures[0].sampler: 4 is out of range; expected an index into samplers (there are 1)"}},
    {"texture-source-out-of-range.gltf", {"textures[0].source: 3 is out of range; expected an index into images (there are 1)"}},
    {"material-texture-out-of-range.gltf",
     {"materials[0].pbrMetallicRoughness.baseColorTexture.index: 2 is out of range; expected an index into textures "
      "(there are 1)"}},
    {"image-bufferview-out-of-range.gltf",
     {"images[0].bufferView: 9 is out of range; expected an index into bufferViews (there are 3)"}},
    {"sampler-filter-invalid.gltf", {"", {"samplers[0].magFilter: 1234 is not one of 9728, 9729; linear is used"}}},
    {"material-out-of-range.gltf",
     {"meshes[0].primitives[0].material: 0 is out of range; expected an index into materials (there are 0)"}},
    {"node-cycle.gltf", {"nodes[0].children: the node hierarchy has a cycle through this node"}},
    {"node-own-child.gltf", {"nodes[0].children: the node hierarchy has a cycle through this node"}},
    {"node-two-parents.gltf", {"nodes[2]: the node has more than one parent (glTF requires a tree)"}},
    {"node-chain-100000-cycle.gltf", {"nodes[0].children: the node hierarchy has a cycle through this node"}},
    {"node-scale-infinite.gltf", {"not a valid glTF 2.0 file: number overflow parsing '1e400'"}},
    {"primitive-without-position.gltf", {"meshes[0].primitives[0].attributes: POSITION is required"}},
    {"required-extension.gltf", {"extensionsRequired: 'KHR_texture_basisu' is not supported by this player"}},
    {"uri-escapes-folder.gltf",
     {"meshes[0].primitives[0].attributes.POSITION (accessors[0]) -> bufferViews[0].buffer -> buffers[0].uri: "
      "'../outside.bin' escapes the scene's folder"}},
    {"not-json.gltf",
     {"not a valid glTF 2.0 file: parse error at line 1, column 45: syntax error while parsing value - unexpected end "
      "of input; expected '[', '{', or a literal"}},
    {"top-level-array.gltf", {"the top level: expected a JSON object"}},
    {"texture-png-65535x65535.gltf", {"", {"images[0]: PNG of 65535x65535; expected 1..16384 pixels per side" + kDrawnWhite}}},
    {"texture-png-garbage.gltf", {"", {"images[0]: the PNG data cannot be decoded (corrupt or truncated)" + kDrawnWhite}}},
    {"texture-jpeg-truncated.gltf", {"", {"images[0]: the JPEG data cannot be decoded (corrupt or truncated)" + kDrawnWhite}}},
    {"texture-not-png-or-jpeg.gltf", {"", {"images[0]: expected PNG or JPEG data" + kDrawnWhite}}},
    {"glb-header-only.glb", {"not a valid glTF 2.0 file: the file is 8 bytes; expected a 12-byte GLB header and a JSON chunk"}},
    {"glb-bad-magic.glb", {"not a valid glTF 2.0 file: bytes 0..3 are not the GLB magic 'glTF'"}},
    {"glb-version-1.glb", {"not a valid glTF 2.0 file: GLB header version 1; expected 2"}},
    {"glb-length-mismatch.glb",
     {"not a valid glTF 2.0 file: GLB header length 4096 exceeds the file's 556 bytes (the file is truncated)"}},
    {"glb-json-chunk-past-end.glb",
     {"not a valid glTF 2.0 file: GLB chunk 0 at byte 12: length 556 runs past the end of the file (536 bytes left)"}},
    {"glb-bin-chunk-past-end.glb",
     {"not a valid glTF 2.0 file: GLB chunk 1 at byte 504: length 65536 runs past the end of the file (44 bytes left)"}},
    {"glb-first-chunk-bin.glb",
     {"not a valid glTF 2.0 file: GLB chunk 0 at byte 12: type 0x004E4942; expected JSON (0x4E4F534A) first"}},
    {"glb-two-json-chunks.glb", {"not a valid glTF 2.0 file: GLB chunk 1 at byte 504: a second JSON chunk; expected one"}},
    {"glb-truncated-bin.glb",
     {"not a valid glTF 2.0 file: GLB chunk 1 at byte 504: length 44 runs past the end of the file (36 bytes left)"}},
};

class GltfCorpus : public ::testing::TestWithParam<corpus::Case> {
 protected:
  void SetUp() override {
    std::string name = GetParam().name;
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    dir_ = fs::temp_directory_path() / ("gltf_corpus_test_" + std::to_string(::getpid()) + "_" + name);
    fs::create_directories(dir_);
    path_ = dir_ / GetParam().name;
    const std::string bytes = GetParam().make();
    std::ofstream(path_, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_, path_;
};

// Everything written to stdout and stderr (the file descriptors, where libpng would print) while
// `run` runs.
template <typename F>
std::string console_output(F run) {
  std::fflush(stdout);
  std::fflush(stderr);
  char name[] = "/tmp/gltf_console_XXXXXX";
  const int capture = ::mkstemp(name);
  const int saved_out = ::dup(1), saved_err = ::dup(2);
  ::dup2(capture, 1);
  ::dup2(capture, 2);
  run();
  std::fflush(stdout);
  std::fflush(stderr);
  ::dup2(saved_out, 1);
  ::dup2(saved_err, 2);
  ::close(saved_out);
  ::close(saved_err);
  ::close(capture);
  std::ifstream in(name, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ::unlink(name);
  return text;
}

TEST_P(GltfCorpus, GivesItsVerdictAndPrintsNothing) {
  const auto expected = kVerdicts.find(GetParam().name);
  ASSERT_NE(expected, kVerdicts.end()) << GetParam().name << " has no verdict in kVerdicts";
  scene::Scene out;
  out.name = "untouched";
  scene::LoadReport report;
  bool loaded = false;
  EXPECT_EQ(console_output([&] { loaded = scene::load_gltf(path_, out, report); }), "");
  if (expected->second.error.empty()) {
    ASSERT_TRUE(loaded) << report.error;
    EXPECT_EQ(report.warnings, expected->second.warnings);
    EXPECT_GT(out.triangle_count(), 0u);
    EXPECT_TRUE(std::isfinite(out.bounds.radius()));
  } else {
    EXPECT_FALSE(loaded);
    EXPECT_EQ(report.error, path_.string() + ": " + expected->second.error);
    EXPECT_EQ(out.name, "untouched");
  }
}

INSTANTIATE_TEST_SUITE_P(Files, GltfCorpus, ::testing::ValuesIn(corpus::cases()),
                         [](const ::testing::TestParamInfo<corpus::Case>& case_info) {
                           std::string name = case_info.param.name;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(GltfCorpusGenerator, IsDeterministicWithUniqueNamesAndEnoughFilesForAValidatorComparison) {
  std::set<std::string> names;
  size_t valid = 0;
  for (const corpus::Case& c : corpus::cases()) {
    EXPECT_TRUE(names.insert(c.name).second) << c.name;
    EXPECT_EQ(c.make(), c.make()) << c.name;
    valid += c.valid;
  }
  EXPECT_GE(corpus::cases().size(), 60u);
  EXPECT_GE(valid, 20u);
  EXPECT_EQ(kVerdicts.size(), corpus::cases().size()) << "every verdict names a file the corpus writes";
}

// Khronos' glTF-Validator on the same files, as tools/validate-corpus --update stored its verdicts:
// a file with validator errors is refused, one without loads, unless the disagreement is listed
// with its reason. The loader's side is kVerdicts, which the test above holds the loader to.
std::map<std::string, std::string> read_table(const std::string& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in) << file << ": cannot open";
  std::map<std::string, std::string> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const size_t tab = line.find('\t');
    EXPECT_NE(tab, std::string::npos) << file << ": " << line;
    rows[line.substr(0, tab)] = tab == std::string::npos ? "" : line.substr(tab + 1);
  }
  return rows;
}

TEST(GltfCorpusValidator, EveryFileAgreesWithKhronosValidatorOrIsAListedDisagreement) {
  const auto verdicts = read_table(std::string(PLAYER_CORPUS_DIR) + "/validator_verdicts.tsv");
  const auto listed = read_table(std::string(PLAYER_CORPUS_DIR) + "/validator_disagreements.tsv");
  size_t agree = 0;
  for (const corpus::Case& c : corpus::cases()) {
    const auto row = verdicts.find(c.name);
    ASSERT_NE(row, verdicts.end()) << c.name << ": no validator verdict; run tools/validate-corpus --update";
    const int errors = std::stoi(row->second);  // the errors column; -2: no verdict
    const bool loads = kVerdicts.at(c.name).error.empty();
    const bool agrees = errors >= 0 && (errors > 0) != loads;
    if (errors >= 0) {
      EXPECT_EQ(c.valid, errors == 0) << c.name << ": the corpus' label differs from the validator's";
    }
    if (listed.count(c.name)) {
      EXPECT_FALSE(agrees) << c.name << " is listed as a disagreement but agrees: remove it from the list";
    } else {
      EXPECT_TRUE(agrees) << c.name << ": validator errors " << errors << " (" << row->second << "), loader "
                          << (loads ? "loads it" : "refuses it") << "; fix one, or list it with the reason";
      ++agree;
    }
  }
  for (const auto& [name, reason] : verdicts)
    EXPECT_TRUE(kVerdicts.count(name)) << name << ": a verdict for a file the corpus no longer writes";
  for (const auto& [name, reason] : listed) {
    EXPECT_TRUE(kVerdicts.count(name)) << name << ": listed, but the corpus no longer writes it";
    EXPECT_FALSE(reason.empty()) << name << ": listed without a reason";
  }
  EXPECT_GE(agree, 60u);
}

// What the loaded files hold, beyond loading: where the content is the point of the class.
class GltfCorpusContent : public ::testing::Test {
 protected:
  scene::Scene load(const std::string& name, scene::LoadReport* report_out = nullptr) {
    dir_ = fs::temp_directory_path() / ("gltf_corpus_content_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    const std::string bytes = corpus::bytes_of(name);
    std::ofstream(dir_ / name, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    scene::Scene out;
    scene::LoadReport report;
    EXPECT_TRUE(scene::load_gltf(dir_ / name, out, report)) << report.error;
    if (report_out) *report_out = report;
    return out;
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(GltfCorpusContent, A100000DeepChainAddsUpItsTranslations) {
  const scene::Scene chain = load("valid-node-chain-100000.gltf");
  ASSERT_EQ(chain.instances.size(), 1u);
  // 100,000 steps of 1e-4: the triangle's x range [0, 1] moves to [10, 11].
  EXPECT_NEAR(chain.bounds.min.x, 10.0, 1e-6);
  EXPECT_NEAR(chain.bounds.max.x, 11.0, 1e-6);
}

TEST_F(GltfCorpusContent, FiveThousandNodesShareOneConvertedMesh) {
  const scene::Scene shared = load("valid-5000-nodes-share-a-mesh.gltf");
  EXPECT_EQ(shared.meshes.size(), 1u);
  EXPECT_EQ(shared.instances.size(), 5000u);
  for (const scene::Instance& instance : shared.instances) ASSERT_EQ(instance.mesh, 0);
}

TEST_F(GltfCorpusContent, UnusableTexturesAreOneWhitePixel) {
  for (const char* name : {"texture-png-65535x65535.gltf", "texture-png-garbage.gltf", "texture-jpeg-truncated.gltf"}) {
    const scene::Scene loaded = load(name);
    ASSERT_EQ(loaded.textures.size(), 1u) << name;
    EXPECT_EQ(loaded.textures[0].width, 1) << name;
    EXPECT_EQ(loaded.textures[0].rgba, (std::vector<uint8_t>{255, 255, 255, 255})) << name;
    EXPECT_EQ(loaded.materials.at(static_cast<size_t>(loaded.meshes.at(0).material)).base_color_texture, 0) << name;
  }
  // The same files decode where they are well formed: the white comes from the damage alone.
  EXPECT_EQ(load("valid-texture-jpeg.gltf").textures.at(0).width, 8);
  const scene::Scene png = load("valid-texture-png-grey.gltf");
  EXPECT_EQ(png.textures.at(0).width, 4);
  EXPECT_EQ(png.textures.at(0).rgba.size(), 4u * 4u * 4u);
}

TEST_F(GltfCorpusContent, ImagesAboveTheCallersLimitsAreDrawnWhite) {
  dir_ = fs::temp_directory_path() / ("gltf_corpus_content_" + std::to_string(::getpid()));
  fs::create_directories(dir_);
  const std::string bytes = corpus::bytes_of("valid-texture-png-rgb.gltf");
  std::ofstream(dir_ / "t.gltf", std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  scene::Scene out;
  scene::LoadReport report;
  scene::LoadOptions small;
  small.max_texture_size = 3;  // the PNG is 4x4
  ASSERT_TRUE(scene::load_gltf(dir_ / "t.gltf", out, report, small)) << report.error;
  EXPECT_EQ(report.warnings, (std::vector<std::string>{"images[0]: PNG of 4x4; expected 1..3 pixels per side" + kDrawnWhite}));
  scene::LoadOptions tight;
  tight.image_budget_bytes = 63;  // 4 x 4 x 4 bytes is 64
  ASSERT_TRUE(scene::load_gltf(dir_ / "t.gltf", out, report, tight)) << report.error;
  EXPECT_EQ(report.warnings, (std::vector<std::string>{"images[0]: PNG of 4x4 needs 0 MiB decoded; expected at most 0 MiB for "
                                                       "this image (the per-image limit, or what is left of the scene's)" +
                                                       kDrawnWhite}));
}

}  // namespace
