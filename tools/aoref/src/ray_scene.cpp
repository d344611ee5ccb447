#include "aoref/ray_scene.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <vector>

namespace aoref {
namespace {

struct DeviceDeleter {
  void operator()(RTCDevice device) const { rtcReleaseDevice(device); }
};
struct SceneDeleter {
  void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};
using DevicePtr = std::unique_ptr<RTCDeviceTy, DeviceDeleter>;
using ScenePtr = std::unique_ptr<RTCSceneTy, SceneDeleter>;

void record_error(void* user, RTCError code, const char* message) {
  auto* last = static_cast<std::string*>(user);
  *last = "Embree error " + std::to_string(static_cast<int>(code)) + (message ? std::string(": ") + message : "");
}

}  // namespace

struct RayScene::Impl {
  std::string last_error;  // written by Embree's error callback (build runs on one thread)
  DevicePtr device;
  ScenePtr scene;
  glm::dvec3 origin{0.0};
  double radius = 0.0;
  size_t triangles = 0, skipped = 0;
};

RayScene::RayScene() : impl_(std::make_unique<Impl>()) {}
RayScene::~RayScene() = default;
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;

bool RayScene::build(const scene::Scene& source, std::string& error) {
  auto impl = std::make_unique<Impl>();
  impl->device.reset(rtcNewDevice(nullptr));
  if (!impl->device) {
    error = "Embree: cannot create a device (error " + std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")";
    return false;
  }
  rtcSetDeviceErrorFunction(impl->device.get(), record_error, &impl->last_error);

  // One triangle geometry holding every instance: world = instance matrix (double) x vertex, then
  // made relative to the centre of the vertices' bounds before rounding to float. The bounds are
  // computed here rather than taken from scene.bounds, which a scene built in code may not have set.
  std::vector<glm::dvec3> world_vertices;
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  std::vector<glm::uvec3> triangles;
  for (size_t n = 0; n < source.instances.size(); ++n) {
    const scene::Instance& instance = source.instances[n];
    if (instance.mesh < 0 || static_cast<size_t>(instance.mesh) >= source.meshes.size()) {
      error = source.name + ": instances[" + std::to_string(n) + "].mesh: expected an index below " +
              std::to_string(source.meshes.size()) + ", found " + std::to_string(instance.mesh);
      return false;
    }
    for (const scene::Vertex& v : source.meshes[static_cast<size_t>(instance.mesh)].vertices) {
      const glm::dvec3 world = glm::dvec3(instance.world * glm::dvec4(glm::dvec3(v.position), 1.0));
      world_vertices.push_back(world);
      if (std::isfinite(world.x + world.y + world.z)) lo = glm::min(lo, world), hi = glm::max(hi, world);
    }
  }
  if (world_vertices.size() > std::numeric_limits<uint32_t>::max()) {
    error = source.name + ": more than 2^32 vertices after instancing; expected fewer";
    return false;
  }
  if (lo.x <= hi.x) {
    impl->origin = (lo + hi) * 0.5;
    impl->radius = glm::length(hi - lo) * 0.5;
  }
  std::vector<glm::vec3> vertices;
  vertices.reserve(world_vertices.size());
  for (const glm::dvec3& world : world_vertices) vertices.emplace_back(world - impl->origin);

  size_t first = 0;
  for (const scene::Instance& instance : source.instances) {
    const scene::Mesh& mesh = source.meshes[static_cast<size_t>(instance.mesh)];
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      glm::uvec3 tri;
      bool valid = true;
      for (int k = 0; k < 3; ++k) {
        const uint32_t index = mesh.indices[t + static_cast<size_t>(k)];
        valid = valid && index < mesh.vertices.size();
        tri[k] = static_cast<uint32_t>(first + (valid ? index : 0));
      }
      if (valid) {
        // Area from the float vertices Embree will see: a triangle that rounding collapsed is dropped too.
        const glm::dvec3 a(vertices[tri.x]), b(vertices[tri.y]), c(vertices[tri.z]);
        const double area2 = glm::length(glm::cross(b - a, c - a));
        valid = std::isfinite(area2) && area2 > 0.0;
      }
      if (valid) {
        triangles.push_back(tri);
      } else {
        ++impl->skipped;
      }
    }
    first += mesh.vertices.size();
  }
  if (triangles.empty()) {
    error = source.name + ": expected at least one triangle with non-zero area, found none";
    return false;
  }

  impl->scene.reset(rtcNewScene(impl->device.get()));
  if (!impl->scene) {
    error = "Embree: cannot create a scene (" + impl->last_error + ")";
    return false;
  }
  // Robust mode: no rays slip between triangles that share an edge (watertight corners matter here).
  rtcSetSceneFlags(impl->scene.get(), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl->scene.get(), RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(impl->device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  if (!geometry) {
    error = "Embree: cannot create a triangle geometry (" + impl->last_error + ")";
    return false;
  }
  // rtcSetNewGeometryBuffer pads the allocation as Embree's SIMD loads need.
  auto* vertex_buffer = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices.size()));
  auto* index_buffer = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangles.size()));
  if (!vertex_buffer || !index_buffer) {
    rtcReleaseGeometry(geometry);
    error = "Embree: cannot allocate " + std::to_string(triangles.size()) + " triangles (" + impl->last_error + ")";
    return false;
  }
  for (size_t i = 0; i < vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) vertex_buffer[i * 3 + static_cast<size_t>(k)] = vertices[i][k];
  for (size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) index_buffer[i * 3 + static_cast<size_t>(k)] = triangles[i][k];
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl->scene.get(), geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl->scene.get());
  if (rtcGetDeviceError(impl->device.get()) != RTC_ERROR_NONE || !impl->last_error.empty()) {
    error = "Embree: cannot build the BVH (" + impl->last_error + ")";
    return false;
  }
  impl->triangles = triangles.size();
  impl_ = std::move(impl);
  return true;
}

bool RayScene::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_near, double t_far) const {
  if (!impl_ || !impl_->scene) return false;
  const glm::dvec3 local = origin - impl_->origin;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = static_cast<float>(local.x);
  ray.org_y = static_cast<float>(local.y);
  ray.org_z = static_cast<float>(local.z);
  ray.dir_x = static_cast<float>(direction.x);
  ray.dir_y = static_cast<float>(direction.y);
  ray.dir_z = static_cast<float>(direction.z);
  ray.tnear = static_cast<float>(t_near);
  ray.tfar = static_cast<float>(t_far);
  ray.mask = 0xFFFFFFFFu;
  ray.time = 0.0f;
  ray.flags = 0;
  rtcOccluded1(impl_->scene.get(), &context, &ray);
  // Embree marks a blocked ray by setting tfar to -inf.
  return ray.tfar < 0.0f;
}

// A moved-from RayScene answers like an empty one.
size_t RayScene::triangle_count() const {
  return impl_ ? impl_->triangles : 0;
}
size_t RayScene::skipped_triangles() const {
  return impl_ ? impl_->skipped : 0;
}
double RayScene::scene_radius() const {
  return impl_ ? impl_->radius : 0.0;
}

}  // namespace aoref
