// A tetrahedral mesh ready for ray queries (a 4D bounding-volume hierarchy over its cells) and
// ray-traced ambient occlusion on it.
#pragma once

#include "ao4d/intersect.hpp"
#include "ao4d/mesh.hpp"

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <vector>

namespace ao4d {

inline constexpr std::uint32_t kNoCell = std::numeric_limits<std::uint32_t>::max();

struct RayHit {
    double t = 0;
    std::uint32_t cell = kNoCell;
};

class Scene {
public:
    explicit Scene(TetMesh mesh);

    const TetMesh& mesh() const { return mesh_; }
    const Vec4& normal(std::uint32_t cell) const { return normals_[cell]; }  // unit, zero if degenerate
    Vec4 bounds_min() const { return nodes_.empty() ? Vec4{} : nodes_[0].lo; }
    Vec4 bounds_max() const { return nodes_.empty() ? Vec4{} : nodes_[0].hi; }
    double diagonal() const { return length(bounds_max() - bounds_min()); }

    // First hit with t in (t_min, t_max], ignoring the cell `skip` (the one a ray starts on).
    std::optional<RayHit> closest_hit(const Vec4& origin, const Vec4& dir, double t_min, double t_max,
                                      std::uint32_t skip = kNoCell) const;
    // Whether anything is hit with t in (t_min, t_max]; stops at the first hit found.
    bool occluded(const Vec4& origin, const Vec4& dir, double t_min, double t_max, std::uint32_t skip = kNoCell) const;

private:
    struct Node {
        Vec4 lo, hi;
        std::uint32_t first = 0;  // leaf: first index into order_; inner: index of the second child
        std::uint32_t count = 0;  // leaf: number of cells; 0 marks an inner node (first child is next)
    };
    std::uint32_t build(std::uint32_t begin, std::uint32_t end, std::vector<Vec4>& centroids, std::vector<Vec4>& lo,
                        std::vector<Vec4>& hi);
    template <bool AnyHit>
    std::optional<RayHit> traverse(const Vec4& origin, const Vec4& dir, double t_min, double t_max, std::uint32_t skip) const;

    TetMesh mesh_;
    std::vector<Vec4> normals_;
    std::vector<CellPlane> planes_;     // in BVH leaf order
    std::vector<std::uint32_t> order_;  // leaf order -> cell index
    std::vector<Node> nodes_;
};

struct AoParams {
    double radius = 1.0;  // rays longer than this do not occlude
    int rays = 128;
    std::uint64_t seed = 1;
    bool cosine = false;   // cosine-weighted directions instead of uniform ones
    unsigned threads = 0;  // 0: all hardware threads
};

// AO in [0, 1] at point p with unit normal n: the fraction of hemisphere rays (uniform or
// cosine-weighted) that hit something within the radius. `seed` is the point's own seed
// (see point_seed); `skip` a cell the point lies on, excluded against self-intersection.
double ambient_occlusion(const Scene& scene, const Vec4& p, const Vec4& n, const AoParams& params, std::uint64_t seed,
                         std::uint32_t skip = kNoCell);

// Reports completed work items from the calling thread while workers run.
using ProgressFn = std::function<void(std::size_t done, std::size_t total)>;

// Runs body(i) for i in [0, count) on `threads` threads (0: all hardware threads).
void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& body,
                  const ProgressFn& progress = {});

// AO of many points, point i seeded with point_seed(params.seed, SeedStream::points, i).
std::vector<double> ambient_occlusion(const Scene& scene, std::span<const OrientedPoint> points, const AoParams& params,
                                      const ProgressFn& progress = {});

// AO of every vertex along its vertex normal, for the mesh output; vertex i is seeded with
// point_seed(params.seed, SeedStream::vertices, i). The rays start 1e-6 of the scene size off the
// vertex along its normal, so that a surface the vertex rests on occludes it.
std::vector<double> vertex_ambient_occlusion(const Scene& scene, const AoParams& params, const ProgressFn& progress = {});

}  // namespace ao4d
