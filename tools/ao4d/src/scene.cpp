#include "ao4d/scene.hpp"

#include "ao4d/sampling.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace ao4d {

namespace {

constexpr std::uint32_t kLeafSize = 4;
constexpr int kBins = 16;

// The boundary 3-volume of a 4D box. By Cauchy-Crofton the chance that a random line meets a convex
// body is proportional to its boundary measure, which makes this the 4D surface-area heuristic.
double boundary_volume(const Vec4& lo, const Vec4& hi) {
  const Vec4 e = max(hi - lo, Vec4{});
  return 2.0 * (e.x * e.y * e.z + e.x * e.y * e.w + e.x * e.z * e.w + e.y * e.z * e.w);
}

// Entry distance of the ray into the box, or +inf when it misses within [t_min, t_max]. A NaN from
// 0 * inf (a ray in a slab's plane) fails every comparison and so keeps the box, conservatively.
double box_entry(const Vec4& lo, const Vec4& hi, const Vec4& origin, const Vec4& inv_dir, double t_min, double t_max) {
  double t_near = t_min, t_far = t_max;
  for (std::size_t i = 0; i < 4; ++i) {
    double t1 = (lo[i] - origin[i]) * inv_dir[i];
    double t2 = (hi[i] - origin[i]) * inv_dir[i];
    if (t1 > t2) std::swap(t1, t2);
    if (t1 > t_near) t_near = t1;
    if (t2 < t_far) t_far = t2;
  }
  // The slab distances and a cell's plane distance are rounded differently; without this slack a
  // hit on a box face (every flat cell's box is flat) can be pruned by an ulp.
  return t_near <= t_far + 1e-12 * std::abs(t_far) ? t_near : std::numeric_limits<double>::infinity();
}

}  // namespace

Scene::Scene(TetMesh mesh) : mesh_(std::move(mesh)) {
  const std::size_t n = mesh_.cells.size();
  if (n >= kNoCell) throw std::invalid_argument("mesh has too many cells");
  for (const Cell& c : mesh_.cells)
    for (std::uint32_t v : c)
      if (v >= mesh_.vertices.size()) throw std::invalid_argument("mesh cell refers to a missing vertex");
  normals_ = cell_normals(mesh_);
  std::vector<Vec4> centroids(n), lo(n), hi(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Cell& c = mesh_.cells[i];
    lo[i] = hi[i] = mesh_.vertices[c[0]];
    Vec4 sum;
    for (std::uint32_t v : c) {
      lo[i] = min(lo[i], mesh_.vertices[v]);
      hi[i] = max(hi[i], mesh_.vertices[v]);
      sum += mesh_.vertices[v];
    }
    centroids[i] = sum * 0.25;
  }
  order_.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) order_[i] = i;
  if (n > 0) {
    nodes_.reserve(2 * n / kLeafSize + 1);
    build(0, static_cast<std::uint32_t>(n), centroids, lo, hi);
  }
  planes_.reserve(n);
  for (std::uint32_t cell : order_) {
    const Cell& c = mesh_.cells[cell];
    planes_.push_back(make_cell_plane(mesh_.vertices[c[0]], mesh_.vertices[c[1]], mesh_.vertices[c[2]], mesh_.vertices[c[3]]));
  }
}

// Binned SAH split on the axis of largest centroid extent; falls back to a median split when
// the centroids coincide in the bins.
std::uint32_t Scene::build(std::uint32_t begin, std::uint32_t end, std::vector<Vec4>& centroids, std::vector<Vec4>& lo,
                           std::vector<Vec4>& hi) {
  const std::uint32_t index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Vec4 box_lo = lo[order_[begin]], box_hi = hi[order_[begin]];
  Vec4 c_lo = centroids[order_[begin]], c_hi = c_lo;
  for (std::uint32_t i = begin; i < end; ++i) {
    box_lo = min(box_lo, lo[order_[i]]);
    box_hi = max(box_hi, hi[order_[i]]);
    c_lo = min(c_lo, centroids[order_[i]]);
    c_hi = max(c_hi, centroids[order_[i]]);
  }
  nodes_[index].lo = box_lo;
  nodes_[index].hi = box_hi;
  const std::uint32_t count = end - begin;
  auto make_leaf = [&] {
    nodes_[index].first = begin;
    nodes_[index].count = count;
    return index;
  };
  if (count <= kLeafSize) return make_leaf();

  std::size_t axis = 0;
  for (std::size_t i = 1; i < 4; ++i)
    if (c_hi[i] - c_lo[i] > c_hi[axis] - c_lo[axis]) axis = i;
  const double extent = c_hi[axis] - c_lo[axis];
  std::uint32_t mid = begin + count / 2;
  if (extent > 0) {
    struct Bin {
      Vec4 lo{1e300, 1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300, -1e300};
      std::uint32_t count = 0;
    };
    std::array<Bin, kBins> bins;
    auto bin_of = [&](std::uint32_t cell) {
      const int b = static_cast<int>(kBins * (centroids[cell][axis] - c_lo[axis]) / extent);
      return std::clamp(b, 0, kBins - 1);
    };
    for (std::uint32_t i = begin; i < end; ++i) {
      Bin& b = bins[static_cast<std::size_t>(bin_of(order_[i]))];
      b.lo = min(b.lo, lo[order_[i]]);
      b.hi = max(b.hi, hi[order_[i]]);
      ++b.count;
    }
    std::array<double, kBins> left_cost{};
    Bin acc;
    for (int i = 0; i < kBins - 1; ++i) {
      acc.lo = min(acc.lo, bins[static_cast<std::size_t>(i)].lo);
      acc.hi = max(acc.hi, bins[static_cast<std::size_t>(i)].hi);
      acc.count += bins[static_cast<std::size_t>(i)].count;
      left_cost[static_cast<std::size_t>(i)] = acc.count ? boundary_volume(acc.lo, acc.hi) * acc.count : 0;
    }
    acc = Bin{};
    double best = std::numeric_limits<double>::infinity();
    int best_split = -1;
    for (int i = kBins - 1; i > 0; --i) {
      acc.lo = min(acc.lo, bins[static_cast<std::size_t>(i)].lo);
      acc.hi = max(acc.hi, bins[static_cast<std::size_t>(i)].hi);
      acc.count += bins[static_cast<std::size_t>(i)].count;
      const double cost =
          left_cost[static_cast<std::size_t>(i - 1)] + (acc.count ? boundary_volume(acc.lo, acc.hi) * acc.count : 0);
      if (acc.count > 0 && acc.count < count && cost < best) {
        best = cost;
        best_split = i;
      }
    }
    if (best_split > 0) {
      const auto it = std::partition(order_.begin() + begin, order_.begin() + end,
                                     [&](std::uint32_t cell) { return bin_of(cell) < best_split; });
      mid = static_cast<std::uint32_t>(it - order_.begin());
    }
  }
  if (mid == begin || mid == end) {
    mid = begin + count / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](std::uint32_t a, std::uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
  }
  build(begin, mid, centroids, lo, hi);
  const std::uint32_t second = build(mid, end, centroids, lo, hi);
  nodes_[index].first = second;
  nodes_[index].count = 0;
  return index;
}

template <bool AnyHit>
std::optional<RayHit> Scene::traverse(const Vec4& origin, const Vec4& dir, double t_min, double t_max, std::uint32_t skip) const {
  if (nodes_.empty()) return std::nullopt;
  const Vec4 inv{1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z, 1.0 / dir.w};
  std::optional<RayHit> best;
  double t_best = t_max;
  // Depth is bounded by the tree height, which the SAH/median builder keeps near log2(n).
  std::array<std::uint32_t, 128> stack;
  std::size_t top = 0;
  if (box_entry(nodes_[0].lo, nodes_[0].hi, origin, inv, t_min, t_best) == std::numeric_limits<double>::infinity())
    return std::nullopt;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        if (order_[i] == skip) continue;
        if (const auto hit = intersect(planes_[i], origin, dir, t_min, t_best)) {
          if constexpr (AnyHit) return RayHit{hit->t, order_[i]};
          t_best = hit->t;
          best = RayHit{hit->t, order_[i]};
        }
      }
      continue;
    }
    const std::uint32_t a = static_cast<std::uint32_t>(&node - nodes_.data()) + 1, b = node.first;
    const double ta = box_entry(nodes_[a].lo, nodes_[a].hi, origin, inv, t_min, t_best);
    const double tb = box_entry(nodes_[b].lo, nodes_[b].hi, origin, inv, t_min, t_best);
    if (top + 2 > stack.size()) throw std::logic_error("BVH deeper than the traversal stack");
    // Push the farther child first so the nearer one is searched first and shrinks t_best.
    const bool a_first = ta <= tb;
    const std::uint32_t near = a_first ? a : b, far = a_first ? b : a;
    const double t_near = a_first ? ta : tb, t_far = a_first ? tb : ta;
    if (t_far != std::numeric_limits<double>::infinity()) stack[top++] = far;
    if (t_near != std::numeric_limits<double>::infinity()) stack[top++] = near;
  }
  return best;
}

std::optional<RayHit> Scene::closest_hit(const Vec4& origin, const Vec4& dir, double t_min, double t_max,
                                         std::uint32_t skip) const {
  return traverse<false>(origin, dir, t_min, t_max, skip);
}

bool Scene::occluded(const Vec4& origin, const Vec4& dir, double t_min, double t_max, std::uint32_t skip) const {
  return traverse<true>(origin, dir, t_min, t_max, skip).has_value();
}

double ambient_occlusion(const Scene& scene, const Vec4& p, const Vec4& n, const AoParams& params, std::uint64_t seed,
                         std::uint32_t skip) {
  if (params.rays <= 0) return 0.0;
  Rng rng(seed);
  // Rays start on the surface; a tiny relative t_min rejects re-hitting the surface the point lies
  // on (rounding puts p a little below it) without hiding genuine nearby occluders.
  const double t_min = 1e-9 * std::max(scene.diagonal(), params.radius);
  int hits = 0;
  for (int i = 0; i < params.rays; ++i) {
    const Vec4 dir = params.cosine ? cosine_hemisphere(rng, n) : uniform_hemisphere(rng, n);
    if (scene.occluded(p, dir, t_min, params.radius, skip)) ++hits;
  }
  return static_cast<double>(hits) / params.rays;
}

void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& body, const ProgressFn& progress) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(count, 1)));
  // Small chunks balance uneven work (empty voxels next to hit ones) without contention.
  constexpr std::size_t kChunk = 64;
  std::atomic<std::size_t> next{0}, done{0};
  std::exception_ptr error;
  std::atomic<bool> failed{false};
  std::mutex error_mutex;
  auto worker = [&] {
    try {
      for (;;) {
        const std::size_t begin = next.fetch_add(kChunk);
        if (begin >= count || failed.load()) return;
        const std::size_t end = std::min(count, begin + kChunk);
        for (std::size_t i = begin; i < end; ++i) body(i);
        done.fetch_add(end - begin);
      }
    } catch (...) {
      const std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads);
  for (unsigned i = 0; i < threads; ++i) pool.emplace_back(worker);
  if (progress) {
    while (done.load() < count && !failed.load()) {
      progress(done.load(), count);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  if (progress) progress(count, count);
}

std::vector<double> ambient_occlusion(const Scene& scene, std::span<const OrientedPoint> points, const AoParams& params,
                                      const ProgressFn& progress) {
  std::vector<double> ao(points.size());
  parallel_for(
      points.size(), params.threads,
      [&](std::size_t i) {
        ao[i] = ambient_occlusion(scene, points[i].position, points[i].normal, params,
                                  point_seed(params.seed, SeedStream::points, i));
      },
      progress);
  return ao;
}

std::vector<double> vertex_ambient_occlusion(const Scene& scene, const AoParams& params, const ProgressFn& progress) {
  const std::vector<Vec4> normals = vertex_normals(scene.mesh());
  std::vector<double> ao(normals.size(), 0.0);
  // A vertex can rest on another surface, as the pyramids' base vertices rest on the floor of the
  // two-tetrahedra scene. Rays from the vertex itself would cross that surface at t = 0, below
  // ambient_occlusion's t_min, and every ray into the floor would count as open (all 18 vertices of
  // that scene got AO 0). So the rays start a hair off the vertex along its normal, 1e-6 of the
  // scene size, far above t_min. Its own cells do not get in the way: where they form a convex
  // corner the vertex normal, a positive sum of their normals, keeps every hemisphere ray outside
  // them; where they fold inwards, the rays they catch do enter the object.
  const double offset = 1e-6 * std::max(scene.diagonal(), params.radius);
  parallel_for(
      normals.size(), params.threads,
      [&](std::size_t i) {
        if (length(normals[i]) == 0) return;  // only degenerate cells around it: no hemisphere to sample
        ao[i] = ambient_occlusion(scene, scene.mesh().vertices[i] + offset * normals[i], normals[i], params,
                                  point_seed(params.seed, SeedStream::vertices, i));
      },
      progress);
  return ao;
}

}  // namespace ao4d
