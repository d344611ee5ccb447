#include "render/edge_subdivision.h"

#include <algorithm>
#include <array>
#include <map>

namespace render {
namespace {

std::vector<lightfield::Module> checked_modules(const lightfield::ModulesDisplay& display) {
  const int count = static_cast<int>(display.module_x.size());
  std::vector<lightfield::Module> modules;
  const int checked = std::min(count, 16);
  for (int i = 0; i < checked; ++i)
    modules.push_back(
        lightfield::module_of(display, checked == 1 ? 0 : static_cast<int>(std::lround(i * (count - 1.0) / (checked - 1)))));
  return modules;
}

// The worst error of an edge over the modules and the instances that place the mesh.
double edge_error(const std::vector<lightfield::Module>& modules, const std::vector<glm::dmat4>& placements,
                  const lightfield::RoiTransform& roi, const glm::vec3& a, const glm::vec3& b) {
  double worst = 0.0;
  for (const glm::dmat4& world : placements) {
    const glm::dvec3 pa = roi.to_physical(glm::dvec3(world * glm::dvec4(glm::dvec3(a), 1.0)));
    const glm::dvec3 pb = roi.to_physical(glm::dvec3(world * glm::dvec4(glm::dvec3(b), 1.0)));
    for (const lightfield::Module& module : modules) worst = std::max(worst, lightfield::edge_error_pixels(module, pa, pb));
  }
  return worst;
}

scene::Vertex midpoint(const scene::Vertex& a, const scene::Vertex& b) {
  scene::Vertex m;
  m.position = (a.position + b.position) * 0.5f;
  const glm::vec3 normal = a.normal + b.normal;
  m.normal = glm::dot(normal, normal) > 1e-12f ? glm::normalize(normal) : a.normal;
  m.uv = (a.uv + b.uv) * 0.5f;
  return m;
}

using EdgeKey = std::pair<uint32_t, uint32_t>;
EdgeKey key(uint32_t a, uint32_t b) {
  return a < b ? EdgeKey{a, b} : EdgeKey{b, a};
}

}  // namespace

scene::Scene subdivide_for_modules(const scene::Scene& input, const lightfield::ModulesDisplay& display,
                                   const lightfield::RoiTransform& roi, double max_error_px, SubdivisionReport& report,
                                   int max_passes, size_t max_triangles) {
  scene::Scene scene = input;
  report = SubdivisionReport{};
  const std::vector<lightfield::Module> modules = checked_modules(display);
  std::vector<std::vector<glm::dmat4>> placements(scene.meshes.size());
  for (const scene::Instance& instance : scene.instances)
    placements[static_cast<size_t>(instance.mesh)].push_back(instance.world);
  size_t triangles = 0;
  for (const scene::Mesh& mesh : scene.meshes) triangles += mesh.indices.size() / 3;
  report.triangles_before = triangles;

  for (int pass = 0; pass <= max_passes; ++pass) {
    // Which edges are too far from straight, measured fresh each pass (the first pass's worst is
    // the report's "before"; the last measurement its "after").
    std::vector<std::map<EdgeKey, uint32_t>> splits(scene.meshes.size());
    double worst = 0.0;
    size_t added = 0;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
      const scene::Mesh& mesh = scene.meshes[m];
      if (placements[m].empty()) continue;
      std::map<EdgeKey, double> measured;
      for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
          const EdgeKey edge = key(mesh.indices[t + static_cast<size_t>(e)], mesh.indices[t + static_cast<size_t>((e + 1) % 3)]);
          auto [it, fresh] = measured.try_emplace(edge, 0.0);
          if (fresh)
            it->second =
                edge_error(modules, placements[m], roi, mesh.vertices[edge.first].position, mesh.vertices[edge.second].position);
          worst = std::max(worst, it->second);
          if (it->second > max_error_px) splits[m].try_emplace(edge, 0u);
        }
      added += splits[m].size() * 3;  // at most: each split adds up to three triangles to its two neighbours
    }
    if (pass == 0) report.worst_before_px = worst;
    report.worst_after_px = worst;
    bool any = false;
    for (const auto& s : splits) any = any || !s.empty();
    if (!any || pass == max_passes) break;
    if (triangles + added > max_triangles) {
      report.capped = true;
      break;
    }
    triangles = 0;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
      scene::Mesh& mesh = scene.meshes[m];
      for (auto& [edge, index] : splits[m]) {
        index = static_cast<uint32_t>(mesh.vertices.size());
        mesh.vertices.push_back(midpoint(mesh.vertices[edge.first], mesh.vertices[edge.second]));
        // The optional streams stay as long as the vertices (scene::Mesh).
        if (!mesh.tangents.empty()) {
          const glm::vec4 a = mesh.tangents[edge.first], b = mesh.tangents[edge.second];
          const glm::vec3 sum = glm::vec3(a) + glm::vec3(b);
          const float length = glm::length(sum);
          mesh.tangents.push_back(length > 1e-12f ? glm::vec4(sum / length, a.w) : a);
        }
        if (!mesh.uv1.empty()) mesh.uv1.push_back((mesh.uv1[edge.first] + mesh.uv1[edge.second]) * 0.5f);
      }
      std::vector<uint32_t> indices;
      indices.reserve(mesh.indices.size() * 2);
      for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        std::array<uint32_t, 3> v{mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
        std::array<int64_t, 3> mid{};  // mid[e]: the midpoint of edge v[e] - v[e + 1], or -1
        int split_count = 0;
        for (int e = 0; e < 3; ++e) {
          const auto it = splits[m].find(key(v[static_cast<size_t>(e)], v[static_cast<size_t>((e + 1) % 3)]));
          mid[static_cast<size_t>(e)] = it == splits[m].end() ? -1 : static_cast<int64_t>(it->second);
          split_count += it == splits[m].end() ? 0 : 1;
        }
        const auto emit = [&](int64_t a, int64_t b, int64_t c) {
          indices.insert(indices.end(), {static_cast<uint32_t>(a), static_cast<uint32_t>(b), static_cast<uint32_t>(c)});
        };
        if (split_count == 0) {
          emit(v[0], v[1], v[2]);
        } else if (split_count == 3) {
          emit(v[0], mid[0], mid[2]);
          emit(mid[0], v[1], mid[1]);
          emit(mid[2], mid[1], v[2]);
          emit(mid[0], mid[1], mid[2]);
        } else {
          // Rotate so that edge 0 (v0 - v1) is split and, with two splits, edge 1 is the other one;
          // the winding stays that of (v0, v1, v2).
          int r = 0;
          if (split_count == 1) {
            while (mid[static_cast<size_t>(r)] < 0) ++r;
          } else {
            while (!(mid[static_cast<size_t>(r)] >= 0 && mid[static_cast<size_t>((r + 1) % 3)] >= 0)) ++r;
          }
          const int64_t a = v[static_cast<size_t>(r)], b = v[static_cast<size_t>((r + 1) % 3)],
                        c = v[static_cast<size_t>((r + 2) % 3)];
          const int64_t ab = mid[static_cast<size_t>(r)], bc = mid[static_cast<size_t>((r + 1) % 3)];
          if (split_count == 1) {
            emit(a, ab, c);
            emit(ab, b, c);
          } else {
            emit(ab, b, bc);
            emit(a, ab, bc);
            emit(a, bc, c);
          }
        }
      }
      mesh.indices = std::move(indices);
      triangles += mesh.indices.size() / 3;
    }
    report.passes = pass + 1;
  }
  report.triangles_after = 0;
  for (const scene::Mesh& mesh : scene.meshes) report.triangles_after += mesh.indices.size() / 3;
  return scene;
}

}  // namespace render
