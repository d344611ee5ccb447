#pragma once
// The scene's GPU data: vertex and index buffers, textures, materials and the draw list. Uploads
// either at once or in slices of a byte budget across frames, so a new item never stalls a frame.
#include "gl/caps.h"
#include "gl/objects.h"
#include "scene/animation.h"
#include "scene/scene.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace render {

// An environment on the GPU: the prefiltered cube map and the irradiance coefficients.
struct EnvironmentGpu {
  gl::Texture specular;  // cube map, RGBA16F, a level per roughness step
  int levels = 0;
  std::array<glm::vec4, 9> irradiance{};
  const scene::Environment* source = nullptr;  // which one is uploaded (the scene keeps it alive)
};

class SceneGpu {
 public:
  struct Mesh {
    gl::VertexArray vao;
    gl::Buffer vertices, indices;
    gl::Buffer tangents, uv1;          // only where the scene's mesh has them
    gl::Buffer joints, joint_weights;  // a skinned mesh's
    // A morphed mesh's positions at the previous pose (attribute 7, the MOTION variants'); other
    // meshes give their own positions there.
    gl::Buffer previous_positions;
    GLsizei index_count = 0;
  };
  struct Draw {
    int mesh;
    int material;
    glm::dmat4 world;
    glm::dvec3 box_centre;  // of the mesh's box, in the mesh: blended draws are sorted by it
    int node = -1;          // the rig's node that moves it (scene::Instance), -1: nothing does
    glm::dmat4 offset{1.0};
    // A skinned draw's skin (scene::Instance::skin, -1: none) and its first joint's index in
    // joint_matrices(); `world` is then its anchor, the skin's first joint.
    int skin = -1;
    int joint_base = 0;
    // `world` before the last pose (its anchor's, for a skinned draw): where the MOTION variants
    // find the surface the previous frame drew.
    glm::dmat4 previous_world{1.0};
  };

  // Starts uploading `scene` (kept alive until the upload ends). Nothing is drawable until ready().
  void begin(std::shared_ptr<const scene::Scene> scene, const gl::Caps& caps);
  // Uploads up to about `budget_bytes` (at least one slice) and returns true once all is on the GPU.
  // On failure returns true with failed() set and the reason in error().
  bool step(size_t budget_bytes);
  // begin() and every step() at once.
  bool upload(const scene::Scene& scene, const gl::Caps& caps, std::string& error);

  bool ready() const { return ready_; }
  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }

  const std::vector<Mesh>& meshes() const { return meshes_; }
  const std::vector<gl::Texture>& textures() const { return textures_; }
  const std::vector<scene::Material>& materials() const { return materials_; }
  // Grouped by G-buffer variant (one program switch per group), alpha-tested last: they lose early
  // depth rejection and are drawn over the depth the others have laid.
  const std::vector<Draw>& draws() const { return draws_; }
  // An animated scene's node tree and animations (null: nothing moves), and the draws placed at
  // the node transforms of a pose of this rig, its morphed meshes shaped at the pose's weights
  // (reshaped on the CPU and their vertices sent again, only when a weight changed); allocates
  // nothing.
  const std::shared_ptr<const scene::Rig>& rig() const { return rig_; }
  void pose(const scene::Pose& pose);
  // The skinned draws' joint matrices (RGBA32F, three texels per joint: the rows of the affine matrix
  // from the draw's mesh to its anchor; 64 joints to a row), empty without skins. The second half of
  // its rows holds the same at the previous pose.
  const gl::Texture& joint_matrices() const { return joint_matrices_; }
  // Counts the poses that moved a draw: the AO of an earlier count is not this scene's any more.
  std::uint64_t pose_version() const { return pose_version_; }
  // The draws of blended materials (alphaMode BLEND), drawn after the opaque image by the forward
  // pass; light field modules draw them in the G-buffer, alpha-tested at their cutoff.
  const std::vector<Draw>& blended_draws() const { return blended_; }
  // The frame's back-to-front order of blended_draws(): sized once the scene is uploaded, so the
  // frame loop sorts without allocating.
  std::vector<std::pair<double, int>>& blend_order() const { return blend_order_; }
  // The scene's world-space box, known once ready().
  const scene::Bounds& bounds() const { return bounds_; }
  double radius() const { return radius_; }
  glm::dvec3 centre() const { return centre_; }
  size_t bytes() const { return bytes_; }  // uploaded so far
  // What lights the scene (its own environment, else the built-in studio), known once ready().
  const EnvironmentGpu& environment() const { return environment_; }
  // The scene's own lights (a LightParams block) and how many, known once ready().
  const gl::Buffer& lights() const { return lights_; }
  int light_count() const { return light_count_; }

 private:
  void finish();
  void upload_environment();

  std::shared_ptr<const scene::Scene> source_;
  int max_texture_size_ = 0;
  size_t mesh_cursor_ = 0, texture_cursor_ = 0;
  size_t offset_ = 0;  // bytes of the current mesh, or rows of the current texture, already uploaded
  bool ready_ = false;
  std::string error_;
  std::vector<Mesh> meshes_;
  std::vector<gl::Texture> textures_;
  std::vector<scene::Material> materials_;
  std::vector<Draw> draws_, blended_;
  mutable std::vector<std::pair<double, int>> blend_order_;
  scene::Bounds bounds_;
  double radius_ = 1.0;
  glm::dvec3 centre_{0.0};
  size_t bytes_ = 0;
  std::shared_ptr<const scene::Environment> environment_source_;
  EnvironmentGpu environment_;
  gl::Buffer lights_;
  int light_count_ = 0;
  std::vector<scene::Light> placed_lights_;  // as the last pose placed them (those nodes move)
  std::shared_ptr<const scene::Rig> rig_;
  std::uint64_t pose_version_ = 0;
  // A mesh the frames reshape (scene::Mesh::morph): its vertices, targets and rest weights as the
  // scene gave them, the node whose weights shape it and the weights its buffer holds now.
  struct Morphed {
    int mesh;
    int node;
    scene::Mesh source;
    std::vector<float> shown;
    std::vector<glm::vec3> positions;  // as its vertex buffer holds them now
    bool moving = false;               // the last pose reshaped it: its previous positions differ
  };
  std::vector<Morphed> morphed_;
  // Writes `draw`'s joint matrices (scene::skin_matrices) into the staging rows, relative to its
  // anchor; true when a row changed.
  bool write_joints(const Draw& draw, const std::vector<glm::dmat4>& skin_matrices);
  void upload_joints();
  gl::Texture joint_matrices_;
  std::vector<glm::vec4> joint_rows_;    // the texture's texels, as the last pose left them
  std::vector<glm::dmat4> pose_joints_;  // one skin's matrices at the pose, sized for the largest
  std::vector<scene::Vertex> shaped_;    // as long as the longest morphed mesh
};

}  // namespace render
