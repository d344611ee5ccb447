#pragma once
// Accessors read with every byte they span checked against their buffer view and buffer, and the
// one error shape of the scene assembly: fail() throws LoadError, which load_gltf turns into the
// report's error (nothing outside the loader sees the exception).
#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <vector>

namespace scene::gltf {

// Far above any scene a single-board computer can draw, low enough that sizes cannot overflow.
constexpr size_t kMaxElements = size_t{1} << 28;

struct LoadError {
  std::string message;
};

[[noreturn]] inline void fail(const std::string& message) {
  throw LoadError{message};
}

size_t component_size(int type);

struct View {
  const unsigned char* data = nullptr;  // null: the accessor has no buffer view, all zeros
  size_t stride = 0;
  size_t count = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;
};

// Checks accessor `index` against the expected shapes and every byte it spans against its buffer view
// and buffer. `field` names the place that refers to it, e.g. "meshes[0].primitives[1].attributes.POSITION".
View checked_view(const tinygltf::Model& model, int index, const std::string& field, std::initializer_list<int> types,
                  int components);

// Component `c` of element `element` as a double (normalised integers scaled to [0, 1] or [-1, 1]);
// 0 for an accessor without a buffer view.
double component(const View& view, size_t element, int c);

// Every element of a float-vector accessor, refused where a component is not finite.
template <int N>
std::vector<glm::vec<N, float>> read_floats(const tinygltf::Model& model, int index, const std::string& field,
                                            std::initializer_list<int> types) {
  const View view = checked_view(model, index, field, types, N);
  std::vector<glm::vec<N, float>> values(view.count);
  for (size_t i = 0; i < view.count; ++i)
    for (int c = 0; c < N; ++c) {
      const double value = component(view, i, c);
      if (!std::isfinite(value) || std::abs(value) > 3.0e38)
        fail(field + ": element " + std::to_string(i) + " component " + std::to_string(c) + " is " + std::to_string(value) +
             ", expected a finite number");
      values[i][c] = static_cast<float>(value);
    }
  return values;
}

}  // namespace scene::gltf
