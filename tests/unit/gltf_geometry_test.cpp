// Geometry as asset pipelines write it: sparse accessors, accessors without a buffer view,
// KHR_mesh_quantization, EXT_meshopt_compression and KHR_draco_mesh_compression (encoded here with
// meshoptimizer's and Draco's own encoders),
// and the constructs glTF-Validator calls valid that the loader used to refuse. Each decoded mesh is
// compared with the same mesh written plainly.
#include "gltf_fixture.h"

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

namespace {

std::string data_uri(const std::vector<unsigned char>& bytes) {
  return "data:application/octet-stream;base64," + base64(bytes);
}

std::vector<glm::vec3> positions_of(const scene::Scene& scene) {
  std::vector<glm::vec3> out;
  for (const scene::Mesh& mesh : scene.meshes)
    for (uint32_t index : mesh.indices) out.push_back(mesh.vertices.at(index).position);
  return out;
}

// The same, each triangle rotated to start at its smallest vertex: meshopt's index codec keeps
// every triangle and its winding but may rotate it.
std::vector<glm::vec3> triangles_of(const scene::Scene& scene) {
  std::vector<glm::vec3> out = positions_of(scene);
  auto less = [](const glm::vec3& a, const glm::vec3& b) { return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z; };
  for (size_t t = 0; t + 2 < out.size(); t += 3)
    while (less(out[t + 1], out[t]) || less(out[t + 2], out[t]))
      std::rotate(out.begin() + long(t), out.begin() + long(t) + 1, out.begin() + long(t) + 3);
  return out;
}

void expect_near(const std::vector<glm::vec3>& actual, const std::vector<glm::vec3>& expected, float tolerance) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t i = 0; i < actual.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[i][c], expected[i][c], tolerance) << "vertex " << i << " component " << c;
}

class GltfGeometry : public GltfLoader {
 protected:
  // The triangle of triangle() with a sparse substitution on POSITION: vertices 0 and 2 moved.
  json sparse_triangle(std::vector<uint8_t> targets, bool with_buffer_view = true) {
    json doc = triangle();
    std::vector<unsigned char> bytes;
    for (uint8_t target : targets) bytes.push_back(target);
    while (bytes.size() % 4) bytes.push_back(0);
    const size_t values_at = bytes.size();
    for (size_t k = 0; k < targets.size(); ++k) append<float>(bytes, {5.0f + float(k), 6.0f, 7.0f});
    doc["buffers"].push_back({{"byteLength", bytes.size()}, {"uri", data_uri(bytes)}});
    doc["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 0}, {"byteLength", targets.size()}});
    doc["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", values_at}, {"byteLength", targets.size() * 12}});
    doc["accessors"][0]["sparse"] = {
        {"count", targets.size()}, {"indices", {{"bufferView", 2}, {"componentType", 5121}}}, {"values", {{"bufferView", 3}}}};
    if (!with_buffer_view) doc["accessors"][0].erase("bufferView");
    return doc;
  }
};

TEST_F(GltfGeometry, SparseAccessorsReplaceTheNamedElements) {
  expect_near(positions_of(load_ok(write(sparse_triangle({0, 2})))), {{5, 6, 7}, {1, 0, 0}, {6, 6, 7}}, 0.0f);
}

TEST_F(GltfGeometry, ASparseAccessorWithoutABufferViewStartsFromZeros) {
  expect_near(positions_of(load_ok(write(sparse_triangle({1}, false)))), {{0, 0, 0}, {5, 6, 7}, {0, 0, 0}}, 0.0f);
}

TEST_F(GltfGeometry, SparseIndicesMustIncreaseAndStayBelowTheCount) {
  for (const std::vector<uint8_t>& targets : {std::vector<uint8_t>{2, 1}, std::vector<uint8_t>{1, 1}, std::vector<uint8_t>{3}}) {
    const std::string error = error_of(write(sparse_triangle(targets)));
    EXPECT_NE(error.find("meshes[0].primitives[0].attributes.POSITION (accessors[0]).sparse.indices: element " +
                         std::to_string(targets.size() - 1)),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("expected strictly increasing indices below the accessor's count 3"), std::string::npos) << error;
  }
}

TEST_F(GltfGeometry, AnIndexAccessorWithoutABufferViewIsZeros) {
  json doc = triangle();
  doc["accessors"][1].erase("bufferView");
  const scene::Scene loaded = load_ok(write(doc));
  expect_near(positions_of(loaded), {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, 0.0f);
}

// Positions as normalised shorts: allowed by KHR_mesh_quantization only.
json quantized_triangle(bool declare) {
  std::vector<unsigned char> bytes;
  append<int16_t>(bytes, {0, 0, 0, 0, 32767, 0, 0, 0, -32767, 16384, 0, 0});
  json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
      {"buffers", {{{"byteLength", bytes.size()}, {"uri", data_uri(bytes)}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", bytes.size()}, {"byteStride", 8}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5122}, {"normalized", true}, {"count", 3}, {"type", "VEC3"}}}}};
  if (declare) doc["extensionsUsed"] = doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  return doc;
}

TEST_F(GltfGeometry, QuantizedPositionsNeedKhrMeshQuantization) {
  expect_near(positions_of(load_ok(write(quantized_triangle(true)))), {{0, 0, 0}, {1, 0, 0}, {-1, 16384.0f / 32767.0f, 0}},
              1e-6f);
  EXPECT_NE(error_of(write(quantized_triangle(false)))
                .find("attributes.POSITION (accessors[0]): signed short normalized is not allowed here; expected float"),
            std::string::npos);
}

// n vertices on a curve (no three in a line), the triangles of a strip written as a list.
struct PlainMesh {
  std::vector<float> positions;
  std::vector<uint16_t> indices;
};
PlainMesh curve_mesh(int n) {
  PlainMesh mesh;
  for (int v = 0; v < n; ++v) mesh.positions.insert(mesh.positions.end(), {float(v), 0.01f * float(v * v), float(v % 3)});
  for (int t = 0; t + 2 < n; ++t)
    mesh.indices.insert(mesh.indices.end(), {uint16_t(t), uint16_t(t + 1 + t % 2), uint16_t(t + 2 - t % 2)});
  return mesh;
}

// The mesh with both buffer views compressed by EXT_meshopt_compression: buffers[0] holds the
// compressed streams, buffers[1] is the fallback without data, as gltfpack writes it.
json meshopt_document(const PlainMesh& mesh, std::vector<unsigned char>* patch_compressed = nullptr) {
  const size_t vertices = mesh.positions.size() / 3;
  std::vector<unsigned char> vertex_stream(meshopt_encodeVertexBufferBound(vertices, 12));
  vertex_stream.resize(
      meshopt_encodeVertexBuffer(vertex_stream.data(), vertex_stream.size(), mesh.positions.data(), vertices, 12));
  std::vector<unsigned char> index_stream(meshopt_encodeIndexBufferBound(mesh.indices.size(), vertices));
  index_stream.resize(
      meshopt_encodeIndexBuffer(index_stream.data(), index_stream.size(), mesh.indices.data(), mesh.indices.size()));
  std::vector<unsigned char> compressed = vertex_stream;
  while (compressed.size() % 4) compressed.push_back(0);
  const size_t index_at = compressed.size();
  compressed.insert(compressed.end(), index_stream.begin(), index_stream.end());
  if (patch_compressed) *patch_compressed = compressed;
  const size_t vertex_bytes = vertices * 12, index_bytes = mesh.indices.size() * 2;
  return {{"asset", {{"version", "2.0"}}},
          {"extensionsUsed", {"EXT_meshopt_compression"}},
          {"extensionsRequired", {"EXT_meshopt_compression"}},
          {"scenes", {{{"nodes", {0}}}}},
          {"nodes", {{{"mesh", 0}}}},
          {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
          {"buffers",
           {{{"byteLength", compressed.size()}, {"uri", data_uri(compressed)}},
            {{"byteLength", vertex_bytes + index_bytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}},
          {"bufferViews",
           {{{"buffer", 1},
             {"byteLength", vertex_bytes},
             {"byteStride", 12},
             {"extensions",
              {{"EXT_meshopt_compression",
                {{"buffer", 0},
                 {"byteLength", vertex_stream.size()},
                 {"byteStride", 12},
                 {"count", vertices},
                 {"mode", "ATTRIBUTES"}}}}}},
            {{"buffer", 1},
             {"byteOffset", vertex_bytes},
             {"byteLength", index_bytes},
             {"extensions",
              {{"EXT_meshopt_compression",
                {{"buffer", 0},
                 {"byteOffset", index_at},
                 {"byteLength", index_stream.size()},
                 {"byteStride", 2},
                 {"count", mesh.indices.size()},
                 {"mode", "TRIANGLES"}}}}}}}},
          {"accessors",
           {{{"bufferView", 0}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC3"}},
            {{"bufferView", 1}, {"componentType", 5123}, {"count", mesh.indices.size()}, {"type", "SCALAR"}}}}};
}

TEST_F(GltfGeometry, MeshoptCompressedViewsDecodeToThePlainMesh) {
  const PlainMesh mesh = curve_mesh(200);
  const scene::Scene plain = load_ok(write(triangle(mesh.positions, mesh.indices), "scene/plain.gltf"));
  const scene::Scene decoded = load_ok(write(meshopt_document(mesh), "scene/meshopt.gltf"));
  EXPECT_EQ(decoded.triangle_count(), 198u);
  expect_near(triangles_of(decoded), triangles_of(plain), 0.0f);
}

TEST_F(GltfGeometry, MeshoptRequestsAreCheckedBeforeDecoding) {
  const PlainMesh mesh = curve_mesh(50);
  struct Case {
    const char* what;
    std::function<void(json&)> change;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"more elements than the view holds",
       [](json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 51; },
       "bufferViews[0].extensions.EXT_meshopt_compression: count x byteStride is 612 bytes; the buffer view has 600"},
      {"a terabyte from a few bytes",
       [](json& d) {
         d["buffers"][1]["byteLength"] = (uint64_t{1} << 40) + 4096;
         d["bufferViews"][0]["byteLength"] = uint64_t{1} << 40;
         d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = (uint64_t{1} << 40) / 12;
       },
       "exceeds the limit of"},
      {"a large view from a few bytes",
       [](json& d) {
         d["buffers"][1]["byteLength"] = 1u << 24;
         d["bufferViews"][0]["byteLength"] = 1u << 24;
         d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = (1u << 24) / 16;
         d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 16;
         d["bufferViews"][0]["byteStride"] = 16;
       },
       "cannot come from"},
      {"an unknown mode", [](json& d) { d["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["mode"] = "STRIPS"; },
       "bufferViews[1].extensions.EXT_meshopt_compression.mode: \"STRIPS\"; expected \"ATTRIBUTES\", \"TRIANGLES\" or "
       "\"INDICES\""},
      {"a mode that is not a string", [](json& d) { d["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["mode"] = 3; },
       "bufferViews[1].extensions.EXT_meshopt_compression.mode: 3; expected"},
      {"a filter that is not a string",
       [](json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["filter"] = json::array(); },
       "bufferViews[0].extensions.EXT_meshopt_compression.filter: []; expected"},
      {"a stride the index codec cannot have",
       [](json& d) { d["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 3; },
       "byteStride: 3; expected 2 or 4 for TRIANGLES"},
      {"compressed bytes beyond their buffer",
       [](json& d) { d["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 100000; },
       "lie beyond its buffer of"},
  };
  for (const Case& c : cases) {
    json doc = meshopt_document(mesh);
    c.change(doc);
    const std::string error = error_of(write(doc));
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.what << ": " << error;
  }
}

TEST_F(GltfGeometry, CorruptMeshoptDataIsRefusedByName) {
  const PlainMesh mesh = curve_mesh(50);
  std::vector<unsigned char> compressed;
  json doc = meshopt_document(mesh, &compressed);
  compressed[0] ^= 0xFF;  // the vertex stream's header byte
  doc["buffers"][0]["uri"] = data_uri(compressed);
  const std::string error = error_of(write(doc));
  EXPECT_NE(error.find("bufferViews[0].extensions.EXT_meshopt_compression: the compressed data cannot be decoded"),
            std::string::npos)
      << error;
}

// The triangles as a sorted list of rotated triangles: Draco's edgebreaker reorders faces too.
std::vector<std::array<float, 9>> sorted_triangles(const scene::Scene& scene) {
  const std::vector<glm::vec3> rotated = triangles_of(scene);
  std::vector<std::array<float, 9>> out;
  for (size_t t = 0; t + 2 < rotated.size(); t += 3) {
    std::array<float, 9> triangle;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) triangle[size_t(k * 3 + c)] = rotated[t + size_t(k)][c];
    out.push_back(triangle);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The mesh as one Draco-compressed buffer view (lossless: no quantization), as gltf-pipeline writes it.
json draco_document(const PlainMesh& plain, std::string* compressed_out = nullptr) {
  draco::TriangleSoupMeshBuilder builder;
  const size_t faces = plain.indices.size() / 3;
  builder.Start(static_cast<int>(faces));
  const int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  for (size_t f = 0; f < faces; ++f) {
    const float* p[3];
    for (int k = 0; k < 3; ++k) p[k] = &plain.positions[size_t(plain.indices[f * 3 + size_t(k)]) * 3];
    builder.SetAttributeValuesForFace(position, draco::FaceIndex(static_cast<uint32_t>(f)), p[0], p[1], p[2]);
  }
  std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  draco::Encoder encoder;
  draco::EncoderBuffer encoded;
  EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &encoded).ok());
  std::vector<unsigned char> bytes(encoded.data(), encoded.data() + encoded.size());
  if (compressed_out) compressed_out->assign(encoded.data(), encoded.size());
  const size_t length = bytes.size();
  while (bytes.size() % 4) bytes.push_back(0);
  return {{"asset", {{"version", "2.0"}}},
          {"extensionsUsed", {"KHR_draco_mesh_compression"}},
          {"extensionsRequired", {"KHR_draco_mesh_compression"}},
          {"scenes", {{{"nodes", {0}}}}},
          {"nodes", {{{"mesh", 0}}}},
          {"meshes",
           {{{"primitives",
              {{{"attributes", {{"POSITION", 0}}},
                {"indices", 1},
                {"extensions",
                 {{"KHR_draco_mesh_compression",
                   {{"bufferView", 0}, {"attributes", {{"POSITION", mesh->attribute(position)->unique_id()}}}}}}}}}}}}},
          {"buffers", {{{"byteLength", bytes.size()}, {"uri", data_uri(bytes)}}}},
          {"bufferViews", {{{"buffer", 0}, {"byteLength", length}}}},
          {"accessors",
           {{{"componentType", 5126}, {"count", mesh->num_points()}, {"type", "VEC3"}},
            {{"componentType", 5125}, {"count", faces * 3}, {"type", "SCALAR"}}}}};
}

TEST_F(GltfGeometry, DracoCompressedPrimitivesDecodeToThePlainMesh) {
  const PlainMesh mesh = curve_mesh(120);
  const scene::Scene plain = load_ok(write(triangle(mesh.positions, mesh.indices), "scene/plain.gltf"));
  const scene::Scene decoded = load_ok(write(draco_document(mesh), "scene/draco.gltf"));
  EXPECT_EQ(decoded.triangle_count(), 118u);
  EXPECT_EQ(sorted_triangles(decoded), sorted_triangles(plain));
}

TEST_F(GltfGeometry, DracoDataThatDoesNotMatchItsPrimitiveIsRefusedByName) {
  const PlainMesh mesh = curve_mesh(30);
  struct Case {
    const char* what;
    std::function<void(json&)> change;
    std::string expected;
  };
  const std::string draco = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";
  const std::vector<Case> cases = {
      {"a point count the accessor does not declare", [](json& d) { d["accessors"][0]["count"] = 7; },
       draco + ".attributes.POSITION: accessors[0].count 7 differs from the decoded mesh's"},
      {"an index count the accessor does not declare", [](json& d) { d["accessors"][1]["count"] = 3; },
       "meshes[0].primitives[0].indices: accessors[1].count 3 differs from the decoded mesh's 84 indices"},
      {"an attribute id the mesh does not have",
       [](json& d) { d["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["POSITION"] = 9; },
       draco + ".attributes.POSITION: the decoded mesh has no attribute with id 9"},
      {"an attribute the primitive does not list",
       [](json& d) { d["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 0; },
       draco + ".attributes.NORMAL: the primitive has no attribute NORMAL"},
      {"an uncompressed POSITION with fewer vertices than the Draco mesh has points",
       [](json& d) {
         d["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"] = json::object();
         d["accessors"][0]["count"] = 3;
       },
       "meshes[0].primitives[0].attributes.POSITION: 3 vertices, but the Draco mesh has"},
      {"ids and indices written as floats",
       [](json& d) {
         auto& compressed = d["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"];
         compressed["bufferView"] = 0.0;
         compressed["attributes"]["POSITION"] = compressed["attributes"]["POSITION"].get<double>();
       },
       ""},
      {"points instead of triangles", [](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 4.0; }, ""},
      {"a strip", [](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 5; },
       "meshes[0].primitives[0].mode: 5; KHR_draco_mesh_compression holds a triangle list, expected mode 4"},
  };
  for (const Case& c : cases) {
    json doc = draco_document(mesh);
    c.change(doc);
    if (c.expected.empty()) {
      EXPECT_EQ(load_ok(write(doc)).triangle_count(), 28u) << c.what;
      continue;
    }
    const std::string error = error_of(write(doc));
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.what << ": " << error;
  }
  std::string compressed;
  json doc = draco_document(mesh, &compressed);
  std::vector<unsigned char> corrupt(compressed.begin(), compressed.begin() + long(compressed.size() / 2));
  while (corrupt.size() % 4) corrupt.push_back(0);
  doc["buffers"][0] = {{"byteLength", corrupt.size()}, {"uri", data_uri(corrupt)}};
  doc["bufferViews"][0]["byteLength"] = corrupt.size();
  const std::string error = error_of(write(doc));
  EXPECT_NE(error.find(draco + ": the compressed mesh cannot be decoded"), std::string::npos) << error;
}

TEST_F(GltfGeometry, IntegersWrittenAsFloatsAreIntegers) {
  json doc = triangle();
  doc["nodes"][0]["mesh"] = 0.0;
  doc["accessors"][0]["count"] = 3.0;
  EXPECT_EQ(load_ok(write(doc)).triangle_count(), 1u);
  // Inside extensions as well: every non-negative integer check reads 3.0 as 3.
  json compressed = meshopt_document(curve_mesh(20));
  compressed["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 12.0;
  compressed["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["buffer"] = 0.0;
  EXPECT_EQ(load_ok(write(compressed, "scene/meshopt.gltf")).triangle_count(), 18u);
  doc["nodes"][0]["mesh"] = 0.5;
  const std::string error = error_of(write(doc));
  EXPECT_NE(error.find("nodes[0].mesh: 0.5 is out of range; expected an index into meshes"), std::string::npos) << error;
}

// A few bytes of JSON can ask for gigabytes (a count on an accessor without a buffer view, a
// compressed view's size); what a scene decodes in all is bounded and checked before allocating.
TEST_F(GltfGeometry, WhatAFileDecodesInAllIsBoundedBeforeAllocating) {
  json doc = triangle();
  doc["accessors"][0] = {{"componentType", 5126}, {"count", 1 << 28}, {"type", "VEC3"}};  // 3 GiB of zeros
  doc["meshes"][0]["primitives"][0].erase("indices");
  EXPECT_NE(error_of(write(doc))
                .find("meshes[0].primitives[0].attributes.POSITION (accessors[0]): decoding it would bring "
                      "the scene to 3221225472 bytes of decoded data; the limit is 2147483648 bytes"),
            std::string::npos);

  // Each accessor within the budget, the two together beyond it: the second is refused.
  const PlainMesh mesh = curve_mesh(200);
  const fs::path path = write(triangle(mesh.positions, mesh.indices));
  scene::LoadOptions options;
  options.decoded_budget_bytes = 200 * 12 + 100;
  scene::Scene out;
  scene::LoadReport report;
  EXPECT_FALSE(scene::load_gltf(path, out, report, options));
  EXPECT_NE(report.error.find("meshes[0].primitives[0].indices (accessors[1]): decoding it would bring the scene to"),
            std::string::npos)
      << report.error;
  options.decoded_budget_bytes = 200 * 12 + 198 * 3 * 4;
  EXPECT_TRUE(scene::load_gltf(path, out, report, options)) << report.error;

  // Decompressed views count too.
  options.decoded_budget_bytes = 1000;
  EXPECT_FALSE(scene::load_gltf(write(meshopt_document(mesh), "scene/meshopt.gltf"), out, report, options));
  EXPECT_NE(report.error.find("extensions.EXT_meshopt_compression: decoding it would bring the scene to"), std::string::npos)
      << report.error;
}

TEST_F(GltfGeometry, BuffersNothingReadsAreNeverOpened) {
  json doc = triangle();
  doc["buffers"].push_back({{"byteLength", 64}});                                       // no uri, in a .gltf
  doc["buffers"].push_back({{"byteLength", 64}, {"uri", "http://example.com/a.bin"}});  // never fetched
  doc["buffers"].push_back({{"byteLength", 64}, {"uri", "missing.bin"}});
  doc["accessors"].push_back({{"componentType", 5126}, {"count", 3}, {"type", "NotaVEC3"}});  // unknown, unread
  EXPECT_EQ(load_ok(write(doc)).triangle_count(), 1u);
  doc["bufferViews"][0]["buffer"] = 1;
  EXPECT_NE(error_of(write(doc))
                .find("attributes.POSITION (accessors[0]) -> bufferViews[0].buffer -> buffers[1]: has no uri; expected a uri "
                      "(only buffers[0] of a .glb may use the BIN chunk)"),
            std::string::npos);
  doc["bufferViews"][0]["buffer"] = 2;
  EXPECT_NE(error_of(write(doc)).find("buffers[2].uri: 'http://example.com/a.bin' is a URL"), std::string::npos);
  doc["bufferViews"][0]["buffer"] = 0;
  doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 2;
  EXPECT_NE(error_of(write(doc)).find("(accessors[2]).type: \"NotaVEC3\" is not a glTF accessor type"), std::string::npos);
}

TEST_F(GltfGeometry, DataUrisInBase64OrPercentEncoding) {
  json doc = triangle();
  // The same bytes, percent-encoded: RFC 2397 without ";base64".
  static const char* hex = "0123456789ABCDEF";
  std::string percent = "data:application/octet-stream,";
  scene::Scene reference = load_ok(write(doc));
  {
    std::vector<unsigned char> raw;
    for (float p : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append<float>(raw, {p});
    append<uint16_t>(raw, {0, 1, 2, 0});
    for (unsigned char b : raw) percent += std::string("%") + hex[b >> 4] + hex[b & 15];
  }
  doc["buffers"][0]["uri"] = percent;
  expect_near(positions_of(load_ok(write(doc))), positions_of(reference), 0.0f);
  doc["buffers"][0]["uri"] = "data:application/octet-stream;base64,AAA*";
  EXPECT_NE(error_of(write(doc)).find("the data: URI's base64 has '*' at character 3"), std::string::npos);
  doc["buffers"][0]["uri"] = "data:application/octet-stream,%G0";
  EXPECT_NE(error_of(write(doc)).find("malformed %-escape"), std::string::npos);
}

TEST_F(GltfGeometry, ExtensionsTheFileUsesButThePlayerDoesNotReadAreNamedOnce) {
  json doc = triangle();
  doc["extensionsUsed"] = {"KHR_texture_basisu", "KHR_mesh_quantization"};
  scene::Scene out;
  scene::LoadReport report;
  ASSERT_TRUE(scene::load_gltf(write(doc), out, report)) << report.error;
  EXPECT_EQ(report.warnings, std::vector<std::string>{"extensionsUsed: 'KHR_texture_basisu' is not supported; textures whose "
                                                      "only source is in that format are drawn white"});
  doc["extensionsRequired"] = {"KHR_texture_basisu"};
  EXPECT_NE(error_of(write(doc)).find("extensionsRequired: 'KHR_texture_basisu' is not supported by this player"),
            std::string::npos);
}

}  // namespace
