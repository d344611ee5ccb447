// Materials as files describe them: which texture coordinate set a texture reads, and
// KHR_texture_transform, baked into the mesh's UVs at load and checked against the extension's
// formula computed here.
#include "gltf_fixture.h"

#include <OpenImageIO/imageio.h>

#include <cmath>

namespace {

class GltfMaterial : public GltfLoader {
 protected:
  // triangle() with two UV sets and a 2x2 base colour texture reading set `set`.
  json textured(int set) {
    const fs::path png = dir_ / "scene" / "albedo.png";
    const unsigned char pixels[2 * 2 * 3] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    auto output = OIIO::ImageOutput::create(png.string());
    EXPECT_TRUE(output && output->open(png.string(), OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::UINT8)));
    EXPECT_TRUE(output->write_image(OIIO::TypeDesc::UINT8, pixels));
    output->close();
    json doc = triangle();
    std::vector<unsigned char> bytes;
    for (const glm::vec2& uv : kSet0) append<float>(bytes, {uv.x, uv.y});
    for (const glm::vec2& uv : kSet1) append<float>(bytes, {uv.x, uv.y});
    doc["buffers"].push_back({{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}});
    doc["bufferViews"].push_back({{"buffer", 1}, {"byteLength", 24}});
    doc["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 24}, {"byteLength", 24}});
    doc["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
    doc["accessors"].push_back({{"bufferView", 3}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
    doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2;
    doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = 3;
    doc["meshes"][0]["primitives"][0]["material"] = 0;
    doc["images"] = {{{"uri", "albedo.png"}}};
    doc["textures"] = {{{"source", 0}}};
    doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", set}}}}}}};
    return doc;
  }

  std::vector<glm::vec2> uvs_of(const json& doc) {
    const scene::Scene loaded = load_ok(write(doc));
    std::vector<glm::vec2> out;
    for (uint32_t index : loaded.meshes.at(0).indices) out.push_back(loaded.meshes[0].vertices.at(index).uv);
    return out;
  }

  const std::vector<glm::vec2> kSet0 = {{0, 0}, {1, 0}, {0, 1}};
  const std::vector<glm::vec2> kSet1 = {{0.25f, 0.25f}, {0.75f, 0.25f}, {0.25f, 0.75f}};
};

void expect_uvs(const std::vector<glm::vec2>& actual, const std::vector<glm::vec2>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t i = 0; i < actual.size(); ++i) {
    EXPECT_NEAR(actual[i].x, expected[i].x, 1e-6f) << "vertex " << i;
    EXPECT_NEAR(actual[i].y, expected[i].y, 1e-6f) << "vertex " << i;
  }
}

TEST_F(GltfMaterial, ATextureReadsTheSetItsTexCoordNames) {
  expect_uvs(uvs_of(textured(0)), kSet0);
  expect_uvs(uvs_of(textured(1)), kSet1);
}

// The extension's formula: scale, then rotate counter-clockwise as the image is seen (v down),
// then offset: (u, v) -> (sx u cos r + sy v sin r + ox, -sx u sin r + sy v cos r + oy).
glm::vec2 transformed(glm::vec2 uv, glm::vec2 offset, float rotation, glm::vec2 scale) {
  const double u = double(scale.x) * uv.x, v = double(scale.y) * uv.y, c = std::cos(rotation), s = std::sin(rotation);
  return glm::vec2(float(u * c + v * s + offset.x), float(-u * s + v * c + offset.y));
}

TEST_F(GltfMaterial, KhrTextureTransformIsBakedIntoTheUvs) {
  for (const float rotation : {0.0f, 0.392699f, 1.5707963f, -2.0f}) {
    json doc = textured(1);
    doc["extensionsUsed"] = doc["extensionsRequired"] = {"KHR_texture_transform"};
    doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
        {"KHR_texture_transform", {{"offset", {0.5, -0.25}}, {"rotation", rotation}, {"scale", {2, 3}}}}};
    std::vector<glm::vec2> expected;
    for (const glm::vec2& uv : kSet1) expected.push_back(transformed(uv, {0.5f, -0.25f}, rotation, {2, 3}));
    expect_uvs(uvs_of(doc), expected);
  }
}

TEST_F(GltfMaterial, TheTransformsTexCoordReplacesTheTextureInfos) {
  json doc = textured(1);
  doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"offset", {1, 2}}, {"texCoord", 0}}}};
  expect_uvs(uvs_of(doc), {{1, 2}, {2, 2}, {1, 3}});
  doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"]["texCoord"] = 0.0;
  expect_uvs(uvs_of(doc), {{1, 2}, {2, 2}, {1, 3}});
}

TEST_F(GltfMaterial, AMalformedTransformIsRefusedByField) {
  json doc = textured(0);
  const std::string field = "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform";
  doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"rotation", "x"}}}};
  EXPECT_NE(error_of(write(doc)).find(field + ".rotation: expected a finite number"), std::string::npos);
  doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {{"KHR_texture_transform", {{"scale", {1}}}}};
  EXPECT_NE(error_of(write(doc)).find(field + ".scale: expected 2 numbers"), std::string::npos);
  doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"scale", {1e300, 1e300}}}}};
  EXPECT_NE(error_of(write(doc)).find("KHR_texture_transform takes a coordinate beyond the float range"), std::string::npos);
}

TEST_F(GltfMaterial, ASetThePrimitiveLacksIsSampledAtTheOriginWithAWarning) {
  json doc = textured(3);
  scene::Scene out;
  scene::LoadReport report;
  ASSERT_TRUE(scene::load_gltf(write(doc), out, report)) << report.error;
  EXPECT_EQ(report.warnings, std::vector<std::string>{"meshes[0].primitives[0].attributes: the material's textures read "
                                                      "TEXCOORD_3, which the primitive lacks; they are sampled at (0, 0)"});
}

// glTF's metallic-roughness material: factors, the four other textures in their colour spaces,
// each on its own mapping where it differs from the base colour's.
TEST_F(GltfMaterial, MetallicRoughnessNormalOcclusionAndEmissiveAreRead) {
  json doc = textured(0);
  // Without pbrMetallicRoughness's factors: glTF's defaults, metallic and rough.
  scene::Material material = load_ok(write(doc)).materials.at(1);
  EXPECT_EQ(material.metallic, 1.0f);
  EXPECT_EQ(material.roughness, 1.0f);
  EXPECT_FALSE(material.normal.present());
  EXPECT_EQ(material.emissive, glm::vec3(0.0f));

  json& m = doc["materials"][0];
  m["pbrMetallicRoughness"]["metallicFactor"] = 0.25;
  m["pbrMetallicRoughness"]["roughnessFactor"] = 0.5;
  m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", 0}};
  m["normalTexture"] = {{"index", 0}, {"scale", 0.75}};
  m["occlusionTexture"] = {{"index", 0}, {"texCoord", 1}, {"strength", 0.5}};
  m["emissiveTexture"] = {{"index", 0}};
  m["emissiveFactor"] = {1.0, 0.5, 0.25};
  scene::Scene loaded = load_ok(write(doc));
  material = loaded.materials.at(1);
  EXPECT_EQ(material.metallic, 0.25f);
  EXPECT_EQ(material.roughness, 0.5f);
  EXPECT_EQ(material.normal_scale, 0.75f);
  EXPECT_EQ(material.occlusion_strength, 0.5f);
  EXPECT_EQ(material.emissive, glm::vec3(1.0f, 0.5f, 0.25f));
  ASSERT_TRUE(material.metallic_roughness.present() && material.normal.present() && material.occlusion.present() &&
              material.emissive_texture.present());
  // The one image read as colour (base colour, emission) and as data (the rest): two textures.
  EXPECT_EQ(material.emissive_texture.texture, material.base_color_texture);
  EXPECT_EQ(material.normal.texture, material.metallic_roughness.texture);
  EXPECT_NE(material.normal.texture, material.base_color_texture);
  EXPECT_TRUE(loaded.textures.at(static_cast<size_t>(material.base_color_texture)).srgb);
  EXPECT_FALSE(loaded.textures.at(static_cast<size_t>(material.normal.texture)).srgb);
  // Occlusion reads TEXCOORD_1, the others the base colour's set: the mesh carries both.
  EXPECT_TRUE(material.occlusion.second_uv);
  EXPECT_FALSE(material.normal.second_uv || material.metallic_roughness.second_uv || material.emissive_texture.second_uv);
  const scene::Mesh& mesh = loaded.meshes.at(0);
  ASSERT_EQ(mesh.uv1.size(), mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    EXPECT_EQ(mesh.vertices[i].uv, kSet0[i]);
    EXPECT_EQ(mesh.uv1[i], kSet1[i]);
  }
  // A normal map brings tangents: generated here (the file has none), in the surface, unit, signed.
  ASSERT_EQ(mesh.tangents.size(), mesh.vertices.size());
  for (const glm::vec4& t : mesh.tangents) {
    EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(glm::vec3(t), glm::vec3(0, 0, 1)), 0.0f, 1e-5f);
    EXPECT_EQ(std::abs(t.w), 1.0f);
  }
  // A scale the shader's floats cannot carry through (its square overflows) is held at 10^4, with a warning.
  m["normalTexture"]["scale"] = -1e30;
  scene::Scene steep;
  scene::LoadReport report;
  ASSERT_TRUE(scene::load_gltf(write(doc), steep, report)) << report.error;
  EXPECT_EQ(steep.materials.at(1).normal_scale, -1e4f);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("materials[0].normalTexture.scale: "), std::string::npos);
}

TEST_F(GltfMaterial, EmissiveStrengthScalesTheEmission) {
  json doc = textured(0);
  doc["materials"][0]["emissiveFactor"] = {1.0, 0.5, 0.0};
  doc["materials"][0]["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}};
  doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  scene::Scene out;
  scene::LoadReport report;
  ASSERT_TRUE(scene::load_gltf(write(doc), out, report)) << report.error;
  EXPECT_EQ(out.materials.at(1).emissive, glm::vec3(4.0f, 2.0f, 0.0f));
  EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
  doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = -1;
  EXPECT_NE(error_of(write(doc))
                .find("materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength: expected a "
                      "number from 0 to 1e6"),
            std::string::npos);
}

// A third distinct mapping in one material is more than the mesh carries: sampled with the first.
TEST_F(GltfMaterial, AThirdMappingIsSampledWithTheFirstWithAWarning) {
  json doc = textured(0);
  doc["materials"][0]["occlusionTexture"] = {{"index", 0}, {"texCoord", 1}};
  doc["materials"][0]["emissiveTexture"] = {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0.0}}}}}}};
  scene::Scene out;
  scene::LoadReport report;
  ASSERT_TRUE(scene::load_gltf(write(doc), out, report)) << report.error;
  EXPECT_FALSE(out.materials.at(1).emissive_texture.second_uv);
  EXPECT_EQ(report.warnings, std::vector<std::string>{"materials[0].emissiveTexture: a third texture coordinate mapping in one "
                                                      "material; sampled with the first"});
}

// The file's TANGENT is used when the material has a normal map and the mesh its normals.
TEST_F(GltfMaterial, TheFilesTangentsAreKeptNormalised) {
  json doc = textured(0);
  std::vector<unsigned char> normals_and_tangents;
  for (int i = 0; i < 3; ++i) append<float>(normals_and_tangents, {0, 0, 1});
  for (int i = 0; i < 3; ++i) append<float>(normals_and_tangents, {0, 2, 0, -1});
  doc["buffers"].push_back({{"byteLength", normals_and_tangents.size()},
                            {"uri", "data:application/octet-stream;base64," + base64(normals_and_tangents)}});
  doc["bufferViews"].push_back({{"buffer", 2}, {"byteLength", 36}});
  doc["bufferViews"].push_back({{"buffer", 2}, {"byteOffset", 36}, {"byteLength", 48}});
  doc["accessors"].push_back({{"bufferView", 4}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  doc["accessors"].push_back({{"bufferView", 5}, {"componentType", 5126}, {"count", 3}, {"type", "VEC4"}});
  doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 4;
  doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = 5;
  EXPECT_TRUE(load_ok(write(doc)).meshes.at(0).tangents.empty());  // no normal map: not read
  doc["materials"][0]["normalTexture"] = {{"index", 0}};
  const scene::Mesh mesh = load_ok(write(doc)).meshes.at(0);
  ASSERT_EQ(mesh.tangents.size(), 3u);
  for (const glm::vec4& t : mesh.tangents) EXPECT_EQ(t, glm::vec4(0, 1, 0, -1));
}

// Generated tangents follow the UVs as glTF reads them: on a quad whose u runs along +x and v along
// -y (the image upright, v down it), the tangent is +x and the bitangent (w * cross(n, t)) +y, up
// the image, where a normal map's green channel points.
TEST(Tangents, FollowTheTextureDirections) {
  scene::Mesh mesh;
  mesh.vertices = {{{0, 0, 0}, {0, 0, 1}, {0, 1}},
                   {{1, 0, 0}, {0, 0, 1}, {1, 1}},
                   {{1, 1, 0}, {0, 0, 1}, {1, 0}},
                   {{0, 1, 0}, {0, 0, 1}, {0, 0}}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  scene::generate_tangents(mesh, false);
  ASSERT_EQ(mesh.tangents.size(), 4u);
  for (const glm::vec4& t : mesh.tangents) {
    EXPECT_NEAR(glm::distance(glm::vec3(t), glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
    const glm::vec3 bitangent = t.w * glm::cross(glm::vec3(0, 0, 1), glm::vec3(t));
    EXPECT_NEAR(glm::distance(bitangent, glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
  }
  // Mirrored in u: the tangent turns round, the bitangent stays.
  for (scene::Vertex& v : mesh.vertices) v.uv.x = 1.0f - v.uv.x;
  scene::generate_tangents(mesh, false);
  for (const glm::vec4& t : mesh.tangents) {
    EXPECT_NEAR(glm::distance(glm::vec3(t), glm::vec3(-1, 0, 0)), 0.0f, 1e-6f);
    const glm::vec3 bitangent = t.w * glm::cross(glm::vec3(0, 0, 1), glm::vec3(t));
    EXPECT_NEAR(glm::distance(bitangent, glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
  }
  // No UV area at all: still a unit vector in the surface, never NaN.
  for (scene::Vertex& v : mesh.vertices) v.uv = glm::vec2(0.5f);
  scene::generate_tangents(mesh, false);
  for (const glm::vec4& t : mesh.tangents) {
    EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-6f);
    EXPECT_NEAR(t.z, 0.0f, 1e-6f);
  }
}

TEST_F(GltfMaterial, KhrMaterialsUnlitMarksTheMaterial) {
  json doc = textured(0);
  EXPECT_FALSE(load_ok(write(doc)).materials.at(1).unlit);
  doc["extensionsUsed"] = doc["extensionsRequired"] = {"KHR_materials_unlit"};
  doc["materials"][0]["extensions"] = {{"KHR_materials_unlit", json::object()}};
  EXPECT_TRUE(load_ok(write(doc)).materials.at(1).unlit);
}

// Cameras are read from the nodes that place them, with their world transforms and checked values.
TEST_F(GltfMaterial, CamerasComeWithTheirNodesWorldTransform) {
  json doc = triangle();
  doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}},
                    {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0}, {"zfar", 10}}}}};
  doc["nodes"] = {{{"mesh", 0}},
                  {{"translation", {0, 0, 4}}, {"children", {2}}},
                  {{"camera", 0}, {"translation", {1, 0, 0}}},
                  {{"camera", 1}}};
  doc["scenes"][0]["nodes"] = {0, 1, 3};
  const scene::Scene loaded = load_ok(write(doc));
  ASSERT_EQ(loaded.cameras.size(), 2u);
  EXPECT_TRUE(loaded.cameras[0].perspective);
  EXPECT_DOUBLE_EQ(loaded.cameras[0].yfov, 0.5);
  EXPECT_EQ(loaded.cameras[0].zfar, 0.0);
  EXPECT_EQ(glm::dvec3(loaded.cameras[0].world[3]), glm::dvec3(1, 0, 4));
  EXPECT_FALSE(loaded.cameras[1].perspective);
  EXPECT_EQ(loaded.cameras[0].unplaced, "");
  // A node that scales its camera to nothing places no view: kept, but marked for the note.
  doc["nodes"][2]["scale"] = {1, 0, 1};
  EXPECT_EQ(load_ok(write(doc)).cameras[0].unplaced, "its node's transform scales its view direction or its up to nothing");
  doc["nodes"][2]["scale"] = {1, 1, 1e-200};
  EXPECT_NE(load_ok(write(doc)).cameras[0].unplaced, "");
  doc["nodes"][2].erase("scale");
  doc["cameras"][0]["perspective"]["yfov"] = 0;
  EXPECT_NE(error_of(write(doc)).find("cameras[0].perspective.yfov: 0.000000; expected radians in (0, pi)"), std::string::npos);
  doc["cameras"][0]["perspective"]["yfov"] = 0.5;
  doc["cameras"][0]["perspective"]["zfar"] = 0.05;
  EXPECT_NE(error_of(write(doc)).find("cameras[0].perspective.zfar"), std::string::npos);
}

// KHR_lights_punctual: lights are placed by their nodes' world transforms (a spot and a directional
// light shine along the node's -Z), colour times intensity, glTF's defaults where a value is
// absent; what the extension forbids is refused by field, an unknown type left out with a warning.
TEST_F(GltfMaterial, LightsComeWithTheirNodesWorldTransform) {
  json doc = triangle();
  doc["extensionsUsed"] = {"KHR_lights_punctual"};
  doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 4.0}, {"range", 10.0}},
      {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.4}}}},
      {{"type", "directional"}, {"intensity", 2.0}},
      {{"type", "area"}}};
  // Node 1 turns a quarter about +Y: its -Z points along -X.
  const double s = std::sqrt(0.5);
  doc["nodes"] = {{{"mesh", 0}},
                  {{"translation", {0, 2, 0}}, {"rotation", {0, s, 0, s}}, {"children", {2, 3}}},
                  {{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}, {"translation", {0, 0, -1}}},
                  {{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}},
                  {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"translation", {3, 0, 0}}},
                  {{"extensions", {{"KHR_lights_punctual", {{"light", 3}}}}}}};
  doc["scenes"][0]["nodes"] = {0, 1, 4, 5};
  scene::Scene out;
  scene::LoadReport report;
  ASSERT_TRUE(scene::load_gltf(write(doc), out, report)) << report.error;
  EXPECT_EQ(report.warnings, std::vector<std::string>{"extensions.KHR_lights_punctual.lights[3].type: \"area\" is not a "
                                                      "light type this player knows; the light is left out"});
  ASSERT_EQ(out.lights.size(), 3u);  // in node order: the spot, the directional, the point light
  const scene::Light& spot = out.lights[0];
  EXPECT_EQ(spot.type, scene::Light::Type::spot);
  EXPECT_EQ(spot.node, 2);
  // The child's -1 along its parent's Z, turned a quarter about Y: -1 along world X, 2 up.
  EXPECT_NEAR(glm::distance(spot.position, glm::dvec3(-1, 2, 0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::distance(spot.direction, glm::dvec3(-1, 0, 0)), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(spot.inner_cone, 0.1);
  EXPECT_DOUBLE_EQ(spot.outer_cone, 0.4);
  EXPECT_EQ(spot.color, glm::vec3(1.0f));
  EXPECT_EQ(spot.range, 0.0);
  const scene::Light& directional = out.lights[1];
  EXPECT_EQ(directional.type, scene::Light::Type::directional);
  EXPECT_NEAR(glm::distance(directional.direction, glm::dvec3(-1, 0, 0)), 0.0, 1e-12);
  EXPECT_EQ(directional.color, glm::vec3(2.0f));
  const scene::Light& point = out.lights[2];
  EXPECT_EQ(point.type, scene::Light::Type::point);
  EXPECT_EQ(point.position, glm::dvec3(3, 0, 0));
  EXPECT_EQ(point.color, glm::vec3(4.0f, 2.0f, 1.0f));
  EXPECT_EQ(point.range, 10.0);
  // A spot's defaults: inner 0, outer pi/4.
  doc["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"] = json::object();
  EXPECT_DOUBLE_EQ(load_ok(write(doc)).lights.at(0).outer_cone, 0.7853981633974483);

  auto refused = [&](json changed, const std::string& expected) {
    const std::string error = error_of(write(changed));
    EXPECT_NE(error.find(expected), std::string::npos) << error;
  };
  json bad = doc;
  bad["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"] = {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.4}};
  refused(bad,
          "extensions.KHR_lights_punctual.lights[1].spot: innerConeAngle 0.500000 and outerConeAngle 0.400000; "
          "expected 0 <= innerConeAngle < outerConeAngle <= pi/2");
  bad = doc;
  bad["extensions"]["KHR_lights_punctual"]["lights"][1].erase("spot");
  refused(bad, "lights[1].spot: a spot light requires its cone");
  bad = doc;
  bad["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = -1;
  refused(bad, "lights[0].intensity: -1.000000; expected a number >= 0");
  bad = doc;
  bad["extensions"]["KHR_lights_punctual"]["lights"][0]["range"] = 0;
  refused(bad, "lights[0].range: 0.000000; expected a number > 0");
  bad = doc;
  bad["extensions"]["KHR_lights_punctual"]["lights"][0]["color"] = {1, 2, 0};
  refused(bad, "lights[0].color[1]: expected a number in [0, 1]");
  bad = doc;
  bad["extensions"]["KHR_lights_punctual"]["lights"][0].erase("type");
  refused(bad, "lights[0].type: expected \"directional\", \"point\" or \"spot\"");
  bad = doc;
  bad["nodes"][4]["extensions"]["KHR_lights_punctual"]["light"] = 7;
  refused(bad, "nodes[4].extensions.KHR_lights_punctual.light: 7 out of range (there are 4)");
  bad = doc;
  bad["extensions"].erase("KHR_lights_punctual");
  refused(bad, "nodes[2].extensions.KHR_lights_punctual.light: the file defines no lights");
  // A node scaled to nothing hides its spot (animations do this): left out with a warning.
  json hidden = doc;
  hidden["nodes"][2]["scale"] = {0, 0, 0};
  scene::Scene shown;
  ASSERT_TRUE(scene::load_gltf(write(hidden), shown, report)) << report.error;
  EXPECT_EQ(shown.lights.size(), 2u);
  EXPECT_NE(report.warnings.back().find("nodes[2]: the transform leaves its light no direction"), std::string::npos);
}

// More lights than the renderer shades: the first kMaxLights in node order, and one warning.
TEST_F(GltfMaterial, LightsBeyondTheRenderersRoomAreLeftOutWithOneWarning) {
  json doc = triangle();
  doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}}};
  for (int i = 0; i < 12; ++i) {
    doc["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"translation", {i, 0, 0}}});
    doc["scenes"][0]["nodes"].push_back(i + 1);
  }
  scene::Scene out;
  scene::LoadReport report;
  ASSERT_TRUE(scene::load_gltf(write(doc), out, report)) << report.error;
  ASSERT_EQ(out.lights.size(), scene::kMaxLights);
  EXPECT_EQ(out.lights.back().position, glm::dvec3(scene::kMaxLights - 1, 0, 0));
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("more than 8 lights; the first 8 in node order are shown"), std::string::npos);
}

TEST_F(GltfMaterial, AlphaModesAndCutoffs) {
  json doc = textured(0);
  scene::Scene loaded = load_ok(write(doc));
  EXPECT_EQ(loaded.materials.at(1).alpha_mode, scene::AlphaMode::opaque);
  EXPECT_FALSE(loaded.materials.at(1).alpha_tested());
  doc["materials"][0]["alphaMode"] = "MASK";
  doc["materials"][0]["alphaCutoff"] = 0.25;
  loaded = load_ok(write(doc));
  EXPECT_EQ(loaded.materials.at(1).alpha_mode, scene::AlphaMode::mask);
  EXPECT_FLOAT_EQ(loaded.materials.at(1).alpha_cutoff, 0.25f);
  doc["materials"][0].erase("alphaCutoff");
  EXPECT_FLOAT_EQ(load_ok(write(doc)).materials.at(1).alpha_cutoff, 0.5f);  // glTF's default
  doc["materials"][0]["alphaMode"] = "BLEND";
  scene::Scene out;
  scene::LoadReport report;
  ASSERT_TRUE(scene::load_gltf(write(doc), out, report)) << report.error;
  EXPECT_EQ(out.materials.at(1).alpha_mode, scene::AlphaMode::blend);
  EXPECT_TRUE(out.materials.at(1).alpha_tested());
  EXPECT_EQ(report.warnings, std::vector<std::string>{});  // blended by the forward pass
  doc["materials"][0]["alphaMode"] = "CLEAR";
  EXPECT_NE(error_of(write(doc)).find("materials[0].alphaMode: \"CLEAR\"; expected \"OPAQUE\", \"MASK\" or \"BLEND\""),
            std::string::npos);
}

}  // namespace
