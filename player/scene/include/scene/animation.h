#pragma once
// glTF animation of node transforms: the node tree of the shown scene, the file's animations
// (translation, rotation, scale and morph target weights channels, STEP, LINEAR and CUBICSPLINE
// samplers), the skins that joints of the tree move, and the pose of every node at a time.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <memory>
#include <string>
#include <vector>

namespace scene {

enum class Interpolation { step, linear, cubic_spline };
enum class AnimatedProperty { translation, rotation, scale, weights };

struct AnimationChannel {
  int node = 0;  // index into Rig::nodes
  AnimatedProperty property = AnimatedProperty::translation;
  Interpolation interpolation = Interpolation::linear;
  std::vector<float> times;  // seconds, strictly increasing
  // xyz (translation, scale) or a quaternion as glTF writes it, x y z w; CUBICSPLINE: three per
  // key, in-tangent, value, out-tangent.
  std::vector<glm::vec4> values;
  // A weights channel's instead: `width` weights (the node's mesh's morph targets) per value, in
  // the same order as `values` would hold them.
  size_t width = 0;
  std::vector<float> weights;
};

struct Animation {
  std::string name;
  std::vector<AnimationChannel> channels;
  double duration = 0.0;  // the last key of any channel
};

// glTF's local transform: translation * rotation * scale.
glm::dmat4 trs_matrix(const glm::dvec3& translation, const glm::dquat& rotation, const glm::dvec3& scale);

// The shown scene's nodes, parents before children, and what moves them.
struct Rig {
  struct Node {
    int parent = -1;
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 scale{1.0};
    bool uses_matrix = false;  // a node given by a matrix (glTF forbids animating it)
    glm::dmat4 matrix{1.0};
    glm::dmat4 local() const { return uses_matrix ? matrix : trs_matrix(translation, rotation, scale); }
    // The morph target weights of the node's mesh as the file gives them (the node's, else its
    // mesh's, else zeros); empty where its mesh has no targets.
    std::vector<float> weights;
  };
  std::vector<Node> nodes;
  std::vector<Animation> animations;
  // glTF's skins: the nodes that are its joints, and each joint's inverse bind matrix.
  struct Skin {
    std::vector<int> joints;
    std::vector<glm::dmat4> inverse_bind;
  };
  std::vector<Skin> skins;
  // `selection`: an animation's index, kAllAnimations or kNoAnimation (the rest pose). The loop of
  // the selection: its longest animation's duration.
  static constexpr int kAllAnimations = -1;
  static constexpr int kNoAnimation = -2;
  double duration(int selection) const;
};

// A playlist's or the command line's `animation`: "all", "none", an index or a name. False, with
// what was expected in `error`, for an index or a name the rig does not have (a scene without
// animations has only "all" and "none").
bool select_animation(const Rig* rig, const std::string& spec, int& selection, std::string& error);

// A channel's value at `seconds` (clamped to its first and last keys): STEP holds a key, LINEAR
// interpolates (rotations by slerp along the shorter arc), CUBICSPLINE is glTF's Hermite spline
// (rotations normalised after).
glm::dvec4 sample(const AnimationChannel& channel, double seconds);
// A weights channel's `width` values at `seconds` into `out`, interpolated as sample() does (each
// weight as a scalar).
void sample_weights(const AnimationChannel& channel, double seconds, float* out);

// The world transform of every node of a rig at a time, made without allocating once constructed.
class Pose {
 public:
  explicit Pose(std::shared_ptr<const Rig> rig);
  // Poses the nodes at `seconds` into the selection (wrapped around its duration); the nodes no
  // channel of it moves keep their file transforms.
  void at(int selection, double seconds);
  const std::vector<glm::dmat4>& worlds() const { return worlds_; }
  // Every node's morph target weights at the pose (empty for a node without targets).
  const std::vector<std::vector<float>>& weights() const { return weights_; }
  const Rig& rig() const { return *rig_; }

 private:
  struct Local {
    glm::dvec3 translation;
    glm::dquat rotation;
    glm::dvec3 scale;
  };
  std::shared_ptr<const Rig> rig_;
  std::vector<Local> locals_;
  std::vector<glm::dmat4> worlds_;
  std::vector<std::vector<float>> weights_;
};

struct Scene;
// Places `scene`'s instances, and its lights and cameras, as `pose` (of scene.rig) has posed its
// nodes. The bounds stay those
// of the whole animation (include_animation_in_bounds), so every pose is framed alike.
void pose_instances(Scene& scene, const Pose& pose);
// The lights that moving nodes carry, placed as `pose` has posed them (a light the pose leaves
// without a position or direction stays where it was); true when one moved. Allocates nothing.
struct Light;
bool pose_lights(std::vector<Light>& lights, const Pose& pose);
// The file's cameras that moving nodes carry, placed as `pose` has posed them; allocates nothing.
struct FileCamera;
void pose_cameras(std::vector<FileCamera>& cameras, const Pose& pose);
// Shapes the meshes with morph targets at the weights `pose` gives the nodes that show them (the
// loader gives each such node a mesh of its own).
void pose_meshes(Scene& scene, const Pose& pose);
// Each joint's world transform (of `node_worlds`) times its inverse bind matrix, into `out`
// (resized to the skin's joints).
void skin_matrices(const Rig::Skin& skin, const std::vector<glm::dmat4>& node_worlds, std::vector<glm::dmat4>& out);
// Widens scene.bounds to hold every pose of its animations (each alone and all together, sampled
// 32 times over their loop), so a camera framing the bounds keeps every moving part in view.
void include_animation_in_bounds(Scene& scene);

}  // namespace scene
