#pragma once
// Accessors read with every byte they span checked against their buffer view, sparse substitutions
// checked index by index, and the one error shape of the scene assembly: fail() throws LoadError,
// which load_gltf turns into the report's error (nothing outside the loader sees the exception).
#include <glm/glm.hpp>

#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace scene::gltf {

class Document;

// Far above any scene a single-board computer can draw, low enough that sizes cannot overflow.
constexpr size_t kMaxElements = size_t{1} << 28;

struct LoadError {
  std::string message;
};

[[noreturn]] inline void fail(const std::string& message) {
  throw LoadError{message};
}

size_t component_size(int type);
// "SCALAR" .. "MAT4".
bool known_accessor_type(const std::string& type);

// A component type an attribute may have, and whether it must be normalised.
struct Format {
  int component_type;
  bool normalized;
};

struct View {
  const unsigned char* data = nullptr;  // null: the accessor has no buffer view, all zeros
  size_t stride = 0;
  size_t count = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;
};

// Component `c` of element `element` as a double (normalised integers scaled to [0, 1] or [-1, 1]);
// 0 for an accessor without a buffer view.
double component(const View& view, size_t element, int c);

// Calls `begin(count)` once, then `element(i, values)` for every element of accessor `index`
// (values: its `components` numbers), then again for each element a sparse substitution replaces, in increasing order, so
// the last call for an index is its value. The accessor's format must be one of `formats`.
// `field` names the place that refers to it, e.g. "meshes[0].primitives[1].attributes.POSITION".
void read_accessor(Document& document, int index, const std::string& field, const std::vector<Format>& formats, int components,
                   const std::function<void(size_t)>& begin, const std::function<void(size_t, const double*)>& element);

// Every element of a float-vector accessor, refused where a component is not finite.
template <int N>
std::vector<glm::vec<N, float>> read_floats(Document& document, int index, const std::string& field,
                                            const std::vector<Format>& formats) {
  std::vector<glm::vec<N, float>> values;
  read_accessor(
      document, index, field, formats, N, [&](size_t count) { values.resize(count); },
      [&](size_t i, const double* v) {
        for (int c = 0; c < N; ++c) {
          if (!std::isfinite(v[c]) || std::abs(v[c]) > 3.0e38)
            fail(field + ": element " + std::to_string(i) + " component " + std::to_string(c) + " is " + std::to_string(v[c]) +
                 ", expected a finite number");
          values[i][c] = static_cast<float>(v[c]);
        }
      });
  return values;
}

}  // namespace scene::gltf
