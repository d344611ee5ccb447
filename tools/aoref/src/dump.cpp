#include "aoref/dump.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace aoref {
namespace {

using nlohmann::json;

// Walks a dotted path ("camera.eye") through objects; nullptr when a step is missing.
const json* find(const json& doc, const std::string& path) {
  const json* node = &doc;
  size_t start = 0;
  while (start <= path.size()) {
    const size_t dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!node->is_object() || !node->contains(key)) return nullptr;
    node = &(*node)[key];
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return node;
}

// Each reader sets `error` to "FILE: FIELD: expected ..., found ..." on failure.
class FieldReader {
 public:
  FieldReader(const json& doc, std::string file, std::string& error) : doc_(doc), file_(std::move(file)), error_(error) {}

  bool number(const std::string& field, double& out, bool positive) {
    const json* node = find(doc_, field);
    if (!node || !node->is_number() || !std::isfinite(node->get<double>()) || (positive && node->get<double>() <= 0.0))
      return fail(field, positive ? "a positive finite number" : "a finite number", node);
    out = node->get<double>();
    return true;
  }
  bool integer(const std::string& field, int& out, int min_value) {
    const json* node = find(doc_, field);
    if (!node || !node->is_number_integer() || node->get<long long>() < min_value || node->get<long long>() > 1 << 20)
      return fail(field, "an integer from " + std::to_string(min_value) + " to " + std::to_string(1 << 20), node);
    out = node->get<int>();
    return true;
  }
  bool text(const std::string& field, std::string& out) {
    const json* node = find(doc_, field);
    if (!node || !node->is_string()) return fail(field, "a string", node);
    out = node->get<std::string>();
    return true;
  }
  bool vec3(const std::string& field, glm::dvec3& out) {
    const json* node = find(doc_, field);
    if (!node || !node->is_array() || node->size() != 3) return fail(field, "an array of 3 finite numbers", node);
    for (int i = 0; i < 3; ++i) {
      const json& v = (*node)[static_cast<size_t>(i)];
      if (!v.is_number() || !std::isfinite(v.get<double>())) return fail(field, "an array of 3 finite numbers", node);
      out[i] = v.get<double>();
    }
    return true;
  }
  bool matrix(const std::string& field, glm::dmat4& out) {
    const json* node = find(doc_, field);
    const char* expected = "4 columns of 4 finite numbers";
    if (!node || !node->is_array() || node->size() != 4) return fail(field, expected, node);
    for (int c = 0; c < 4; ++c) {
      const json& column = (*node)[static_cast<size_t>(c)];
      if (!column.is_array() || column.size() != 4) return fail(field, expected, node);
      for (int r = 0; r < 4; ++r) {
        const json& v = column[static_cast<size_t>(r)];
        if (!v.is_number() || !std::isfinite(v.get<double>())) return fail(field, expected, node);
        out[c][r] = v.get<double>();
      }
    }
    return true;
  }
  bool radii(const std::string& field, std::vector<double>& out) {
    const json* node = find(doc_, field);
    const char* expected = "a non-empty array of positive finite numbers, largest first";
    if (!node || !node->is_array() || node->empty()) return fail(field, expected, node);
    out.clear();
    for (const json& v : *node) {
      if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() <= 0.0) return fail(field, expected, node);
      out.push_back(v.get<double>());
      if (out.size() > 1 && out.back() > out[out.size() - 2]) return fail(field, expected, node);
    }
    return true;
  }

 private:
  bool fail(const std::string& field, const std::string& expected, const json* found) {
    std::string shown = found ? found->dump() : std::string("nothing");
    if (shown.size() > 60) shown = shown.substr(0, 57) + "...";
    error_ = file_ + ": " + field + ": expected " + expected + ", found " + shown;
    return false;
  }
  const json& doc_;
  std::string file_;
  std::string& error_;
};

bool read_checked(const std::string& path, int width, int height, int channels, Image& out, std::string& error) {
  if (!read_image(path, out, error)) return false;
  if (out.width != width || out.height != height || out.channels < channels) {
    error = path + ": expected " + std::to_string(width) + "x" + std::to_string(height) + " with at least " +
            std::to_string(channels) + " channel(s) as camera.json says, found " + std::to_string(out.width) + "x" +
            std::to_string(out.height) + " with " + std::to_string(out.channels);
    return false;
  }
  return true;
}

}  // namespace

bool read_dump(const std::string& dir, Dump& out, std::string& error) {
  const std::string base = dir.empty() || dir.back() == '/' ? dir : dir + "/";
  const std::string json_path = base + "camera.json";
  std::ifstream file(json_path);
  if (!file) {
    error = json_path + ": cannot open (is " + dir + " a folder written by `player render --dump`?)";
    return false;
  }
  json doc = json::parse(file, nullptr, false);
  if (doc.is_discarded()) {
    error = json_path + ": not valid JSON";
    return false;
  }
  Dump dump;
  dump.dir = dir;
  int width = 0, height = 0;
  FieldReader read(doc, json_path, error);
  if (!read.text("scene", dump.scene) || !read.integer("width", width, 1) || !read.integer("height", height, 1) ||
      !read.vec3("camera.eye", dump.view.eye) || !read.matrix("camera.view", dump.view_matrix) ||
      !read.matrix("camera.projection", dump.projection) || !read.number("camera.near", dump.near, true) ||
      !read.number("camera.far", dump.far, true) || !read.radii("ao.radii", dump.view.radii) ||
      !read.integer("ao.samples", dump.samples, 1) || !read.number("ao.bias_fraction", dump.bias_fraction, false) ||
      !read.text("ao.pattern", dump.pattern) || !read.text("ao.blur", dump.blur))
    return false;

  if (!read_checked(base + "position.exr", width, height, 4, dump.view.position, error) ||
      !read_checked(base + "normal.exr", width, height, 4, dump.view.normal, error) ||
      !read_checked(base + "depth.exr", width, height, 1, dump.depth, error) ||
      !read_checked(base + "ao_raw.exr", width, height, 1, dump.ao_raw, error) ||
      !read_checked(base + "ao_blurred.exr", width, height, 1, dump.ao_blurred, error))
    return false;
  // Object pixels must carry finite data: the references trace from them.
  for (size_t i = 0; i < dump.view.position.pixel_count(); ++i) {
    if (!dump.view.is_object(i)) continue;
    for (int c = 0; c < 3; ++c) {
      const char* bad = !std::isfinite(dump.view.position.at(i, c)) ? "position.exr"
                        : !std::isfinite(dump.view.normal.at(i, c)) ? "normal.exr"
                                                                    : nullptr;
      if (bad) {
        error = base + bad + ": pixel (" + std::to_string(i % static_cast<size_t>(width)) + ", " +
                std::to_string(i / static_cast<size_t>(width)) + "): expected finite values on an object pixel";
        return false;
      }
    }
  }
  out = std::move(dump);
  return true;
}

}  // namespace aoref
