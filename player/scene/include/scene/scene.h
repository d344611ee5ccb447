#pragma once
// The validated CPU scene: what the renderer uploads. Everything here has been checked (finite
// numbers, indices in range, unit-length or derived normals), so GPU code needs no checks of its own.
#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace scene {

struct Environment;
struct Rig;

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
};

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // a triangle list
  // Streams only some materials need, empty otherwise (or as long as `vertices`): tangents (xyz,
  // and w = +-1 the bitangent's sign, glTF's TANGENT) for a normal map, and a second UV mapping for
  // textures that read other coordinates than the base colour's (TextureSlot::second_uv).
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec2> uv1;
  int material = 0;
  glm::vec3 min{0.0f}, max{0.0f};  // bounds of the positions (an animated morph's: of every shape it takes)
  // Morph targets (glTF 3.7.2.2) kept where an animation changes the weights; a mesh whose weights
  // never change is loaded in its shape and keeps none. `vertices` hold the shape at `weights`.
  struct Morph {
    // Per target, the displacement of each vertex's position and of its normal (empty where the
    // target moves none).
    std::vector<std::vector<glm::vec3>> positions, normals;
    std::vector<float> weights;
    // The file's normals, unnormalised sums are taken from them; empty for a mesh without NORMAL,
    // whose flat normals are made again from each shape's triangles.
    std::vector<glm::vec3> base_normals;
    size_t target_count() const { return weights.size(); }
  };
  Morph morph;
  // Skinning (glTF 3.7.3): per vertex four joints (indices into its skin's joint list) and their
  // weights, which sum to 1; empty for a mesh no skin deforms.
  std::vector<glm::vec<4, uint16_t>> joints;
  std::vector<glm::vec4> joint_weights;
};

// `mesh`'s vertices at `weights` (target_count() of them) into `out` (as long as mesh.vertices):
// positions moved by the weighted displacements from the shape the mesh holds, normals the
// normalised weighted sum of the file's (or each triangle's own for flat normals). Allocates nothing.
void morph_vertices(const Mesh& mesh, const float* weights, std::vector<Vertex>& out);

// `mesh`'s vertices moved by its joints: `matrices` (one per joint of its skin, each already times
// the instance's offset) weighted per vertex; normals by the same blend, normalised. The CPU's
// account of what the vertex stage does. `out` as long as mesh.vertices; allocates nothing.
void skin_vertices(const Mesh& mesh, const std::vector<glm::dmat4>& matrices, std::vector<Vertex>& out);

enum class Filter { nearest, linear };

struct Texture {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // 8-bit RGBA, row 0 at the top
  bool srgb = true;           // colour (sRGB-encoded: base colour, emissive) or data (normals, roughness...)
  Filter mag = Filter::linear;
  bool mipmaps = true;
  bool repeat_s = true, repeat_t = true;
};

// glTF's alphaMode. blend is drawn by the forward pass over the opaque image; where there is none
// (light field modules) as mask at 0.5.
enum class AlphaMode { opaque, mask, blend };

// A material's texture: its index into Scene::textures (-1: none) and which of the mesh's two UV
// mappings it reads (Vertex::uv, or Mesh::uv1 when second_uv).
struct TextureSlot {
  int texture = -1;
  bool second_uv = false;
  bool present() const { return texture >= 0; }
};

// glTF 2.0's metallic-roughness material. The defaults are those of a glTF material without
// pbrMetallicRoughness (metallic and rough); the procedural scenes set their own.
struct Material {
  glm::vec4 base_color{1.0f};
  int base_color_texture = -1;  // index into Scene::textures; reads Vertex::uv
  float metallic = 1.0f, roughness = 1.0f;
  TextureSlot metallic_roughness;  // B metallic, G roughness (glTF)
  TextureSlot normal;              // tangent-space normals; the mesh carries tangents
  float normal_scale = 1.0f;
  TextureSlot occlusion;  // R
  float occlusion_strength = 1.0f;
  glm::vec3 emissive{0.0f};  // linear, KHR_materials_emissive_strength already applied
  TextureSlot emissive_texture;
  bool double_sided = false;
  AlphaMode alpha_mode = AlphaMode::opaque;
  float alpha_cutoff = 0.5f;  // mask: fragments whose alpha is below it are not drawn
  bool unlit = false;         // KHR_materials_unlit: the base colour as it is, neither lit nor occluded
  bool alpha_tested() const { return alpha_mode != AlphaMode::opaque; }
};

struct Instance {
  int mesh = 0;
  glm::dmat4 world{1.0};  // double: scenes may sit far from the origin
  // In an animated scene: the rig's node that places the mesh (world = the node's world * offset),
  // -1 where nothing moves it; offset: what the loader folded in after (recenter_meshes).
  int node = -1;
  glm::dmat4 offset{1.0};
  // A skinned instance: its skin (Rig::skins) and, per joint, the joint's world transform times its
  // inverse bind matrix at the pose the instance is placed at. A vertex v of the mesh goes to
  // sum(weight * skin_matrices[joint] * offset * v); `world` is then only where its draws are
  // anchored (the first joint), as glTF ignores a skinned mesh's own node transform.
  int skin = -1;
  std::vector<glm::dmat4> skin_matrices{};
};

// A light of the file (KHR_lights_punctual), placed by its node: a directional light shines along
// its node's -Z from infinitely far; a point light from its node's origin in every direction; a spot
// light from there along -Z, within its cone. Intensity as glTF gives it (lux for a directional
// light, candela for the others) at unit exposure, as glTF's sample viewer shows it: a white diffuse
// surface facing 1 lux shows 1/pi of the display's white.
struct Light {
  enum class Type { directional, point, spot };
  Type type = Type::directional;
  glm::vec3 color{1.0f};           // linear RGB times intensity
  glm::dvec3 position{0.0};        // world; point and spot
  glm::dvec3 direction{0, 0, -1};  // world, unit: where the light shines; directional and spot
  double range = 0.0;              // beyond it the light falls to nothing (0: unbounded, inverse square only)
  double inner_cone = 0.0, outer_cone = 0.7853981633974483;  // spot: radians from the axis
  int node = -1;                                             // for messages
  int rig_node = -1;                                         // in an animated scene: the rig's node that carries it (-1: none)
};

// Puts `light` where `world` (its node's world transform) places it; false, the light unchanged,
// where that transform gives no finite position or (but for a point light) no direction.
bool place_light(Light& light, const glm::dmat4& world);

// The lights a scene keeps (the renderer's uniform block has room for these; more are left out
// with a warning).
constexpr size_t kMaxLights = 8;

// A camera of the file (glTF's cameras, placed by the node that names them): it looks along its
// node's -Z with +Y up. Orthographic cameras are kept so an item can be told why it is not used.
struct FileCamera {
  glm::dmat4 world{1.0};
  bool perspective = true;
  double yfov = 0.8;  // radians
  double znear = 0.01;
  double zfar = 0.0;  // 0: infinite (fitted to the scene when drawn)
  int node = -1;      // for messages
  int rig_node = -1;  // in an animated scene: the rig's node that carries it (-1: none)
  // Non-empty when the node's transform places no usable view (a zero scale, a non-finite number,
  // a view direction along its up): why, for the note that says the scene is framed instead.
  std::string_view unplaced;
};

// Puts `camera` where `world` (its node's world transform) places it, or says in `unplaced` why
// that transform places no usable view. Allocates nothing.
void place_camera(FileCamera& camera, const glm::dmat4& world);

struct Bounds {
  glm::dvec3 min{0.0}, max{0.0};
  glm::dvec3 centre() const { return (min + max) * 0.5; }
  double radius() const { return glm::length(max - min) * 0.5; }
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;  // never empty: index 0 is the default material
  std::vector<Texture> textures;
  std::vector<Instance> instances;
  std::vector<FileCamera> cameras;  // in the order the shown scene's nodes are visited
  // The file's own lights; when there are any they replace the player's key light (the
  // environment still lights the scene).
  std::vector<Light> lights;
  // What lights it (scene/environment.h): given by whoever shows the scene (a playlist's
  // `environment`, --environment); null: the built-in studio.
  std::shared_ptr<const Environment> environment;
  // The node tree and animations of a file that animates something (scene/animation.h); null:
  // nothing moves. Bounds, cameras and lights are those of the file's rest pose.
  std::shared_ptr<const Rig> rig;
  Bounds bounds;
  size_t triangle_count() const;
};

// Recomputes `bounds` from the instances (the transformed corners of each mesh's box; for a skinned
// one, of the box of the vertices each joint moves, by that joint's matrix).
void update_bounds(Scene& scene);

// Moves each mesh's vertices so their box is centred on the origin and folds the offset into the
// instances' double-precision transforms: the GPU then never subtracts two large floats, so a mesh
// whose coordinates sit far from the origin keeps the precision its file gave it.
void recenter_meshes(Scene& scene);

// Tangents for a normal map from the mesh's positions, normals and UVs (Vertex::uv, or Mesh::uv1
// with `from_uv1`), in MikkTSpace's conventions: per vertex, angle-weighted, orthogonal to the
// normal, w the bitangent's sign (bitangent = w * cross(normal, tangent)). Unlike MikkTSpace it does
// not split vertices whose faces disagree; files exported with their own TANGENT keep them.
void generate_tangents(Mesh& mesh, bool from_uv1);

}  // namespace scene
