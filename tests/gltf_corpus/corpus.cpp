// The corpus generator. Each case starts from one valid triangle and changes the one thing its
// class is about, so a refusal can only come from that change.
#include "corpus.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace corpus {
namespace {
using nlohmann::json;
using Bytes = std::string;

// An 8x8 baseline JPEG (written once by libjpeg through OpenImageIO, quality 50), kept as bytes so
// the corpus does not depend on the encoder's version.
const unsigned char kJpeg[] = {
    0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x10, 0x4A, 0x46, 0x49, 0x46, 0x00, 0x01, 0x01, 0x00, 0x00, 0x01, 0x00, 0x01, 0x00, 0x00, 0xFF,
    0xE1, 0x00, 0x16, 0x45, 0x78, 0x69, 0x66, 0x00, 0x00, 0x49, 0x49, 0x2A, 0x00, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0xFF, 0xDB, 0x00, 0x43, 0x00, 0x10, 0x0B, 0x0C, 0x0E, 0x0C, 0x0A, 0x10, 0x0E, 0x0D, 0x0E, 0x12, 0x11, 0x10, 0x13,
    0x18, 0x28, 0x1A, 0x18, 0x16, 0x16, 0x18, 0x31, 0x23, 0x25, 0x1D, 0x28, 0x3A, 0x33, 0x3D, 0x3C, 0x39, 0x33, 0x38, 0x37, 0x40,
    0x48, 0x5C, 0x4E, 0x40, 0x44, 0x57, 0x45, 0x37, 0x38, 0x50, 0x6D, 0x51, 0x57, 0x5F, 0x62, 0x67, 0x68, 0x67, 0x3E, 0x4D, 0x71,
    0x79, 0x70, 0x64, 0x78, 0x5C, 0x65, 0x67, 0x63, 0xFF, 0xDB, 0x00, 0x43, 0x01, 0x11, 0x12, 0x12, 0x18, 0x15, 0x18, 0x2F, 0x1A,
    0x1A, 0x2F, 0x63, 0x42, 0x38, 0x42, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63,
    0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63,
    0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0xFF, 0xC0, 0x00, 0x11, 0x08, 0x00, 0x08,
    0x00, 0x08, 0x03, 0x01, 0x22, 0x00, 0x02, 0x11, 0x01, 0x03, 0x11, 0x01, 0xFF, 0xC4, 0x00, 0x1F, 0x00, 0x00, 0x01, 0x05, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08,
    0x09, 0x0A, 0x0B, 0xFF, 0xC4, 0x00, 0xB5, 0x10, 0x00, 0x02, 0x01, 0x03, 0x03, 0x02, 0x04, 0x03, 0x05, 0x05, 0x04, 0x04, 0x00,
    0x00, 0x01, 0x7D, 0x01, 0x02, 0x03, 0x00, 0x04, 0x11, 0x05, 0x12, 0x21, 0x31, 0x41, 0x06, 0x13, 0x51, 0x61, 0x07, 0x22, 0x71,
    0x14, 0x32, 0x81, 0x91, 0xA1, 0x08, 0x23, 0x42, 0xB1, 0xC1, 0x15, 0x52, 0xD1, 0xF0, 0x24, 0x33, 0x62, 0x72, 0x82, 0x09, 0x0A,
    0x16, 0x17, 0x18, 0x19, 0x1A, 0x25, 0x26, 0x27, 0x28, 0x29, 0x2A, 0x34, 0x35, 0x36, 0x37, 0x38, 0x39, 0x3A, 0x43, 0x44, 0x45,
    0x46, 0x47, 0x48, 0x49, 0x4A, 0x53, 0x54, 0x55, 0x56, 0x57, 0x58, 0x59, 0x5A, 0x63, 0x64, 0x65, 0x66, 0x67, 0x68, 0x69, 0x6A,
    0x73, 0x74, 0x75, 0x76, 0x77, 0x78, 0x79, 0x7A, 0x83, 0x84, 0x85, 0x86, 0x87, 0x88, 0x89, 0x8A, 0x92, 0x93, 0x94, 0x95, 0x96,
    0x97, 0x98, 0x99, 0x9A, 0xA2, 0xA3, 0xA4, 0xA5, 0xA6, 0xA7, 0xA8, 0xA9, 0xAA, 0xB2, 0xB3, 0xB4, 0xB5, 0xB6, 0xB7, 0xB8, 0xB9,
    0xBA, 0xC2, 0xC3, 0xC4, 0xC5, 0xC6, 0xC7, 0xC8, 0xC9, 0xCA, 0xD2, 0xD3, 0xD4, 0xD5, 0xD6, 0xD7, 0xD8, 0xD9, 0xDA, 0xE1, 0xE2,
    0xE3, 0xE4, 0xE5, 0xE6, 0xE7, 0xE8, 0xE9, 0xEA, 0xF1, 0xF2, 0xF3, 0xF4, 0xF5, 0xF6, 0xF7, 0xF8, 0xF9, 0xFA, 0xFF, 0xC4, 0x00,
    0x1F, 0x01, 0x00, 0x03, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01, 0x02,
    0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09, 0x0A, 0x0B, 0xFF, 0xC4, 0x00, 0xB5, 0x11, 0x00, 0x02, 0x01, 0x02, 0x04, 0x04, 0x03,
    0x04, 0x07, 0x05, 0x04, 0x04, 0x00, 0x01, 0x02, 0x77, 0x00, 0x01, 0x02, 0x03, 0x11, 0x04, 0x05, 0x21, 0x31, 0x06, 0x12, 0x41,
    0x51, 0x07, 0x61, 0x71, 0x13, 0x22, 0x32, 0x81, 0x08, 0x14, 0x42, 0x91, 0xA1, 0xB1, 0xC1, 0x09, 0x23, 0x33, 0x52, 0xF0, 0x15,
    0x62, 0x72, 0xD1, 0x0A, 0x16, 0x24, 0x34, 0xE1, 0x25, 0xF1, 0x17, 0x18, 0x19, 0x1A, 0x26, 0x27, 0x28, 0x29, 0x2A, 0x35, 0x36,
    0x37, 0x38, 0x39, 0x3A, 0x43, 0x44, 0x45, 0x46, 0x47, 0x48, 0x49, 0x4A, 0x53, 0x54, 0x55, 0x56, 0x57, 0x58, 0x59, 0x5A, 0x63,
    0x64, 0x65, 0x66, 0x67, 0x68, 0x69, 0x6A, 0x73, 0x74, 0x75, 0x76, 0x77, 0x78, 0x79, 0x7A, 0x82, 0x83, 0x84, 0x85, 0x86, 0x87,
    0x88, 0x89, 0x8A, 0x92, 0x93, 0x94, 0x95, 0x96, 0x97, 0x98, 0x99, 0x9A, 0xA2, 0xA3, 0xA4, 0xA5, 0xA6, 0xA7, 0xA8, 0xA9, 0xAA,
    0xB2, 0xB3, 0xB4, 0xB5, 0xB6, 0xB7, 0xB8, 0xB9, 0xBA, 0xC2, 0xC3, 0xC4, 0xC5, 0xC6, 0xC7, 0xC8, 0xC9, 0xCA, 0xD2, 0xD3, 0xD4,
    0xD5, 0xD6, 0xD7, 0xD8, 0xD9, 0xDA, 0xE2, 0xE3, 0xE4, 0xE5, 0xE6, 0xE7, 0xE8, 0xE9, 0xEA, 0xF2, 0xF3, 0xF4, 0xF5, 0xF6, 0xF7,
    0xF8, 0xF9, 0xFA, 0xFF, 0xDA, 0x00, 0x0C, 0x03, 0x01, 0x00, 0x02, 0x11, 0x03, 0x11, 0x00, 0x3F, 0x00, 0x44, 0xB5, 0xD2, 0xD1,
    0xCA, 0xEF, 0x07, 0x07, 0x19, 0x08, 0xC7, 0xF9, 0x0A, 0x28, 0xA2, 0xA7, 0x9E, 0xAB, 0xD7, 0x9D, 0xFE, 0x1F, 0xE4, 0x7A, 0xAB,
    0x29, 0xA0, 0xD5, 0xEE, 0xFF, 0x00, 0xAF, 0x91, 0xFF, 0xD9,
};

template <typename T>
void put(Bytes& out, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out.append(raw, sizeof(T));
}

template <typename T>
void put_big(Bytes& out, T value) {
  for (int shift = 8 * (int(sizeof(T)) - 1); shift >= 0; shift -= 8) out += static_cast<char>((value >> shift) & 0xFF);
}

std::string base64(const Bytes& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t chunk = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) chunk |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) chunk |= uint8_t(bytes[i + 2]);
    out += table[(chunk >> 18) & 63];
    out += table[(chunk >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(chunk >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[chunk & 63] : '=';
  }
  return out;
}

uint32_t crc32(const Bytes& bytes) {
  uint32_t crc = 0xFFFFFFFFu;
  for (char c : bytes) {
    crc ^= uint8_t(c);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

// A PNG of `width` x `height` with `channels` 8-bit channels (1 grey, 3 RGB, 4 RGBA); the pixel data
// is zlib with stored (uncompressed) blocks, so no compressor's version can change a byte.
// `declared_width`/`declared_height` go into the header, which lets a case lie about its size.
Bytes png(uint32_t width, uint32_t height, int channels, uint32_t declared_width = 0, uint32_t declared_height = 0) {
  Bytes raw;
  for (uint32_t y = 0; y < height; ++y) {
    raw += '\0';  // filter: none
    for (uint32_t x = 0; x < width * uint32_t(channels); ++x) raw += static_cast<char>((x * 40 + y * 90) & 0xFF);
  }
  Bytes zlib = "\x78\x01";
  for (size_t at = 0; at < raw.size() || at == 0; at += 65535) {
    const uint16_t length = static_cast<uint16_t>(std::min<size_t>(65535, raw.size() - at));
    zlib += at + length >= raw.size() ? '\x01' : '\x00';
    put<uint16_t>(zlib, length);
    put<uint16_t>(zlib, static_cast<uint16_t>(~length));
    zlib += raw.substr(at, length);
    if (raw.empty()) break;
  }
  uint32_t a = 1, b = 0;
  for (char c : raw) {
    a = (a + uint8_t(c)) % 65521;
    b = (b + a) % 65521;
  }
  put_big<uint32_t>(zlib, (b << 16) | a);
  auto chunk = [](const char* type, const Bytes& data) {
    Bytes out;
    put_big<uint32_t>(out, static_cast<uint32_t>(data.size()));
    const Bytes body = type + data;
    out += body;
    put_big<uint32_t>(out, crc32(body));
    return out;
  };
  Bytes header;
  put_big<uint32_t>(header, declared_width ? declared_width : width);
  put_big<uint32_t>(header, declared_height ? declared_height : height);
  const char colour = channels == 1 ? 0 : channels == 3 ? 2 : 6;
  header += Bytes{'\x08', colour, '\0', '\0', '\0'};
  return Bytes("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) + chunk("IDAT", zlib) + chunk("IEND", "");
}

Bytes jpeg() {
  return Bytes(reinterpret_cast<const char*>(kJpeg), sizeof kJpeg);
}

// A document under construction: one buffer to which views are appended, 4-byte aligned.
struct Doc {
  json root;
  Bytes buffer;

  int view(const Bytes& data, int stride = 0) {
    while (buffer.size() % 4) buffer += '\0';
    json v = {{"buffer", 0}, {"byteOffset", buffer.size()}, {"byteLength", data.size()}};
    if (stride) v["byteStride"] = stride;
    buffer += data;
    root["bufferViews"].push_back(v);
    return static_cast<int>(root["bufferViews"].size()) - 1;
  }
  int accessor(int view, int component_type, size_t count, const char* type) {
    root["accessors"].push_back({{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}});
    return static_cast<int>(root["accessors"].size()) - 1;
  }
  int floats(const std::vector<float>& values, const char* type, size_t per) {
    Bytes data;
    for (float v : values) put<float>(data, v);
    return accessor(view(data), 5126, values.size() / per, type);
  }
  json& primitive() { return root["meshes"][0]["primitives"][0]; }
  int image(const Bytes& data, const char* mime) {
    root["images"].push_back({{"uri", std::string("data:") + mime + ";base64," + base64(data)}});
    root["textures"].push_back({{"source", root["images"].size() - 1}});
    root["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", root["textures"].size() - 1}}}}}});
    primitive()["material"] = root["materials"].size() - 1;
    return static_cast<int>(root["images"].size()) - 1;
  }
  json finished() const {
    json out = root;
    if (!buffer.empty()) {
      Bytes padded = buffer;
      while (padded.size() % 4) padded += '\0';
      out["buffers"] = {{{"byteLength", padded.size()}, {"uri", "data:application/octet-stream;base64," + base64(padded)}}};
    }
    return out;
  }
  Bytes gltf() const { return finished().dump(); }
  // The same document as .glb, with the buffer in the BIN chunk.
  Bytes glb() const {
    json out = root;
    Bytes bin = buffer;
    while (bin.size() % 4) bin += '\0';
    if (!bin.empty()) out["buffers"] = {{{"byteLength", bin.size()}}};
    return make_glb(out.dump(), bin);
  }
  static Bytes make_glb(Bytes text, const Bytes& bin) {
    while (text.size() % 4) text += ' ';
    Bytes out = "glTF";
    put<uint32_t>(out, 2);
    put<uint32_t>(out, static_cast<uint32_t>(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size())));
    put<uint32_t>(out, static_cast<uint32_t>(text.size()));
    put<uint32_t>(out, 0x4E4F534A);
    out += text;
    if (!bin.empty()) {
      put<uint32_t>(out, static_cast<uint32_t>(bin.size()));
      put<uint32_t>(out, 0x004E4942);
      out += bin;
    }
    return out;
  }
};

// One triangle in the xy plane with 16-bit indices: the base every case changes.
Doc triangle() {
  Doc doc;
  doc.root = {{"asset", {{"version", "2.0"}, {"generator", "gltf_corpus"}}},
              {"scene", 0},
              {"scenes", {{{"nodes", {0}}}}},
              {"nodes", {{{"mesh", 0}}}},
              {"meshes", {{{"primitives", {{{"attributes", json::object()}}}}}}},
              {"bufferViews", json::array()},
              {"accessors", json::array()}};
  doc.primitive()["attributes"]["POSITION"] = doc.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  doc.root["accessors"][0]["min"] = {0, 0, 0};
  doc.root["accessors"][0]["max"] = {1, 1, 0};
  Bytes indices;
  for (uint16_t i : {0, 1, 2}) put<uint16_t>(indices, i);
  doc.primitive()["indices"] = doc.accessor(doc.view(indices), 5123, 3, "SCALAR");
  return doc;
}

Doc textured() {
  Doc doc = triangle();
  doc.primitive()["attributes"]["TEXCOORD_0"] = doc.floats({0, 0, 1, 0, 0, 1}, "VEC2", 2);
  return doc;
}

Bytes edit(void (*change)(json&)) {
  Doc doc = triangle();
  json out = doc.finished();
  change(out);
  return out.dump();
}

// --- Valid files ------------------------------------------------------------------------------------

Bytes valid_triangle() {
  return triangle().gltf();
}
Bytes valid_triangle_glb() {
  return triangle().glb();
}
Bytes valid_no_indices() {
  Doc doc = triangle();
  doc.primitive().erase("indices");
  return doc.gltf();
}
Bytes valid_u8_indices() {
  Doc doc = triangle();
  doc.primitive()["indices"] = doc.accessor(doc.view(Bytes("\x02\x01\x00", 3)), 5121, 3, "SCALAR");
  return doc.gltf();
}
Bytes valid_u32_indices() {
  Doc doc = triangle();
  Bytes data;
  for (uint32_t i : {0u, 1u, 2u}) put<uint32_t>(data, i);
  doc.primitive()["indices"] = doc.accessor(doc.view(data), 5125, 3, "SCALAR");
  return doc.gltf();
}
Bytes valid_mode(int mode) {
  Doc doc = triangle();
  doc.primitive()["mode"] = mode;
  return doc.gltf();
}
Bytes valid_strip() {
  return valid_mode(5);
}
Bytes valid_fan() {
  return valid_mode(6);
}
Bytes valid_normals() {
  Doc doc = triangle();
  doc.primitive()["attributes"]["NORMAL"] = doc.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  return doc.gltf();
}
Bytes valid_texcoords() {
  return textured().gltf();
}
Bytes valid_texcoords_ushort() {
  Doc doc = triangle();
  Bytes data;
  for (uint16_t v : {0, 0, 65535, 0, 0, 65535}) put<uint16_t>(data, v);
  doc.primitive()["attributes"]["TEXCOORD_0"] = doc.accessor(doc.view(data), 5123, 3, "VEC2");
  doc.root["accessors"].back()["normalized"] = true;
  return doc.gltf();
}
// Positions and normals interleaved with the widest stride glTF allows.
Bytes valid_interleaved(int stride) {
  Doc doc = triangle();
  Bytes data;
  const float positions[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (int v = 0; v < 3; ++v) {
    Bytes element;
    for (float p : positions[v]) put<float>(element, p);
    for (float n : {0.0f, 0.0f, 1.0f}) put<float>(element, n);
    element.resize(static_cast<size_t>(stride), '\0');
    data += element;
  }
  data.resize(static_cast<size_t>(2 * stride + 24));  // the last element ends after its normal
  const int view = doc.view(data, stride);
  doc.primitive()["attributes"]["POSITION"] = doc.accessor(view, 5126, 3, "VEC3");
  doc.root["accessors"].back()["min"] = {0, 0, 0};  // glTF requires POSITION's bounds
  doc.root["accessors"].back()["max"] = {1, 1, 0};
  doc.primitive()["attributes"]["NORMAL"] = doc.accessor(view, 5126, 3, "VEC3");
  doc.root["accessors"].back()["byteOffset"] = 12;
  return doc.gltf();
}
Bytes valid_interleaved_24() {
  return valid_interleaved(24);
}
Bytes valid_stride_252() {
  return valid_interleaved(252);
}
Bytes valid_texture(const Bytes& image, const char* mime) {
  Doc doc = textured();
  doc.image(image, mime);
  return doc.gltf();
}
Bytes valid_png_rgb() {
  return valid_texture(png(4, 4, 3), "image/png");
}
Bytes valid_png_grey() {
  return valid_texture(png(4, 4, 1), "image/png");
}
Bytes valid_png_rgba() {
  return valid_texture(png(4, 4, 4), "image/png");
}
Bytes valid_jpeg() {
  return valid_texture(jpeg(), "image/jpeg");
}
Bytes valid_image_in_glb() {
  Doc doc = textured();
  const int view = doc.view(png(2, 2, 3));
  doc.root["images"] = {{{"bufferView", view}, {"mimeType", "image/png"}}};
  doc.root["textures"] = {{{"source", 0}, {"sampler", 0}}};
  doc.root["samplers"] = {{{"magFilter", 9728}, {"minFilter", 9728}, {"wrapS", 33071}, {"wrapT", 33071}}};
  doc.root["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  doc.primitive()["material"] = 0;
  return doc.glb();
}
Bytes valid_trs() {
  Doc doc = triangle();
  doc.root["nodes"] = {{{"children", {1}}, {"translation", {10, 0, 0}}, {"rotation", {0, 0, 0.7071068, 0.7071068}}},
                       {{"mesh", 0}, {"scale", {2, 2, 2}}}};
  return doc.gltf();
}
Bytes valid_matrix() {
  Doc doc = triangle();
  doc.root["nodes"][0]["matrix"] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 5, 0, 0, 1};
  return doc.gltf();
}
Bytes valid_two_scenes() {
  Doc doc = triangle();
  doc.root["nodes"].push_back({{"mesh", 0}, {"translation", {3, 0, 0}}});
  doc.root["scenes"] = {{{"nodes", {0}}}, {{"nodes", {1}}}};
  doc.root["scene"] = 1;
  return doc.gltf();
}
Bytes valid_lines_and_triangles() {
  Doc doc = triangle();
  json lines = doc.primitive();
  lines["mode"] = 1;
  lines.erase("indices");
  lines["attributes"].erase("POSITION");
  lines["attributes"]["POSITION"] = 0;
  doc.root["meshes"][0]["primitives"].push_back(lines);
  return doc.gltf();
}
Bytes valid_version_2_1() {
  Doc doc = triangle();
  doc.root["asset"]["version"] = "2.1";
  return doc.gltf();
}
Bytes valid_min_version() {
  Doc doc = triangle();
  doc.root["asset"]["minVersion"] = "2.0";
  return doc.gltf();
}
Bytes valid_morph_target() {
  Doc doc = triangle();
  doc.primitive()["targets"] = {{{"POSITION", doc.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3)}}};
  doc.root["accessors"].back()["min"] = {0, 0, 1};
  doc.root["accessors"].back()["max"] = {0, 0, 1};
  doc.root["meshes"][0]["weights"] = {0.5};
  return doc.gltf();
}
Bytes valid_glb_json_only() {
  Doc doc = triangle();
  return Doc::make_glb(doc.finished().dump(), "");
}
Bytes valid_nested_extras() {
  Doc doc = triangle();
  json extras = json::array();
  for (int depth = 0; depth < 100; ++depth) extras = json::array({extras});
  doc.root["extras"] = extras;
  return doc.gltf();
}
Bytes valid_unicode_names() {
  Doc doc = triangle();
  doc.root["nodes"][0]["name"] = "Ünïcödé ノード \"quoted\" [brackets] {braces}";
  return doc.gltf();
}
// 100,000 nodes, each the only child of the one before, the mesh at the end; each step moves by
// 1e-4 so the transforms matter and stay finite.
Bytes valid_node_chain() {
  Doc doc = triangle();
  json nodes = json::array();
  constexpr int kDepth = 100000;
  for (int i = 0; i < kDepth; ++i) {
    json node = {{"translation", {1e-4, 0, 0}}};
    if (i + 1 < kDepth)
      node["children"] = {i + 1};
    else
      node["mesh"] = 0;
    nodes.push_back(node);
  }
  doc.root["nodes"] = nodes;
  return doc.gltf();
}
Bytes valid_shared_mesh() {
  Doc doc = triangle();
  json nodes = json::array(), roots = json::array();
  for (int i = 0; i < 5000; ++i) {
    nodes.push_back({{"mesh", 0}, {"translation", {i % 100, i / 100, 0}}});
    roots.push_back(i);
  }
  doc.root["nodes"] = nodes;
  doc.root["scenes"][0]["nodes"] = roots;
  return doc.gltf();
}
Bytes valid_two_primitives() {
  Doc doc = triangle();
  json second = doc.primitive();
  doc.root["materials"] = {{{"doubleSided", true}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}}};
  second["material"] = 0;
  doc.root["meshes"][0]["primitives"].push_back(second);
  return doc.gltf();
}
Bytes valid_bom() {
  return "\xEF\xBB\xBF" + triangle().gltf();
}
Bytes valid_points_and_camera() {
  Doc doc = triangle();
  doc.root["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
  doc.root["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 5}}});
  doc.root["scenes"][0]["nodes"] = {0, 1};
  return doc.gltf();
}
Bytes valid_extensions_used() {
  Doc doc = triangle();
  doc.root["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  doc.root["materials"] = {{{"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 2.0}}}}}}};
  doc.primitive()["material"] = 0;
  return doc.gltf();
}
Bytes valid_glb_unknown_chunk() {
  Bytes glb = triangle().glb();
  Bytes extra;
  put<uint32_t>(extra, 4);
  put<uint32_t>(extra, 0x5458454E);  // "NEXT": unknown, to be ignored
  extra += "abcd";
  glb += extra;
  const uint32_t length = static_cast<uint32_t>(glb.size());
  std::memcpy(&glb[8], &length, 4);
  return glb;
}

// --- The named defects -------------------------------------------------------------------------------

Bytes empty_glb() {
  return "";
}
Bytes negative_byte_offset() {
  return edit([](json& d) { d["bufferViews"][0]["byteOffset"] = -4; });
}
Bytes version_1() {
  return edit([](json& d) { d["asset"]["version"] = "1.0"; });
}
Bytes min_version_2_1() {
  return edit([](json& d) {
    d["asset"]["version"] = "2.1";
    d["asset"]["minVersion"] = "2.1";
  });
}
Bytes version_missing() {
  return edit([](json& d) { d["asset"].erase("version"); });
}
Bytes json_nested(int depth) {
  Bytes text = triangle().gltf();
  text.pop_back();  // the closing brace, to add "extras" at the end
  text += ",\"extras\":";
  text += Bytes(static_cast<size_t>(depth), '[') + Bytes(static_cast<size_t>(depth), ']') + "}";
  return text;
}
Bytes json_nested_200000() {
  return json_nested(200000);
}
Bytes json_nested_200000_glb() {
  return Doc::make_glb(json_nested(200000), "");
}

// --- Accessors and buffer views ------------------------------------------------------------------------

Bytes stride_below_element() {
  return edit([](json& d) { d["bufferViews"][0]["byteStride"] = 8; });
}
Bytes stride_above_252() {
  return edit([](json& d) { d["bufferViews"][0]["byteStride"] = 256; });
}
Bytes stride_not_multiple_of_4() {
  return edit([](json& d) { d["bufferViews"][0]["byteStride"] = 14; });
}
Bytes position_vec2() {
  return edit([](json& d) {
    d["accessors"][0]["type"] = "VEC2";
    d["accessors"][0].erase("min");
    d["accessors"][0].erase("max");
  });
}
Bytes position_ushort() {
  return edit([](json& d) {
    d["accessors"][0]["componentType"] = 5123;
    d["accessors"][0].erase("min");
    d["accessors"][0].erase("max");
  });
}
Bytes indices_vec2() {
  return edit([](json& d) { d["accessors"][1]["type"] = "VEC2"; });
}
Bytes float_indices() {
  Doc doc = triangle();
  doc.primitive()["indices"] = doc.floats({0, 1, 2}, "SCALAR", 1);
  return doc.gltf();
}
Bytes attribute_counts_differ() {
  Doc doc = triangle();
  doc.primitive()["attributes"]["TEXCOORD_0"] = doc.floats({0, 0, 1, 0}, "VEC2", 2);
  return doc.gltf();
}
Bytes unread_attribute_count_differs() {
  Doc doc = triangle();
  doc.primitive()["attributes"]["COLOR_0"] = doc.floats({1, 1, 1, 1, 1, 1, 1, 1}, "VEC4", 4);
  return doc.gltf();
}
Bytes count_beyond_2_64() {
  // 2^64 does not fit any JSON integer type a parser keeps; it arrives as a float.
  Bytes text = edit([](json& d) { d["accessors"][0]["count"] = 1234567; });
  return text.replace(text.find("1234567"), 7, "18446744073709551616");
}
Bytes offset_beyond_2_64() {
  Bytes text = edit([](json& d) { d["accessors"][0]["byteOffset"] = 7654321; });
  return text.replace(text.find("7654321"), 7, "36893488147419103232");
}
Bytes view_offset_beyond_2_64() {
  Bytes text = edit([](json& d) { d["bufferViews"][0]["byteOffset"] = 7654321; });
  return text.replace(text.find("7654321"), 7, "18446744073709551617");
}
Bytes count_product_overflows() {
  // 2^62 elements of 12 bytes: the byte count wraps around 2^64.
  return edit([](json& d) { d["accessors"][0]["count"] = uint64_t{1} << 62; });
}
Bytes count_above_limit() {
  // Within JSON's exact integers, far beyond any buffer: refused before any size is computed.
  return edit([](json& d) { d["accessors"][0]["count"] = uint64_t{1} << 40; });
}
Bytes count_float() {
  return edit([](json& d) { d["accessors"][0]["count"] = 3.5; });
}
Bytes count_string() {
  return edit([](json& d) { d["accessors"][0]["count"] = "3"; });
}
Bytes count_zero() {
  return edit([](json& d) { d["accessors"][0]["count"] = 0; });
}
Bytes accessor_beyond_view() {
  return edit([](json& d) { d["accessors"][0]["count"] = 4; });
}
Bytes view_beyond_buffer() {
  return edit([](json& d) { d["bufferViews"][0]["byteLength"] = 1000; });
}
Bytes accessor_unaligned() {
  return edit([](json& d) {
    d["bufferViews"][0]["byteLength"] = 40;
    d["accessors"][0]["byteOffset"] = 2;
  });
}
Bytes index_beyond_vertices() {
  Doc doc = triangle();
  Bytes indices;
  for (uint16_t i : {0, 1, 7}) put<uint16_t>(indices, i);
  doc.primitive()["indices"] = doc.accessor(doc.view(indices), 5123, 3, "SCALAR");
  return doc.gltf();
}
Bytes nan_position() {
  Doc doc = triangle();
  doc.primitive()["attributes"]["POSITION"] =
      doc.floats({0, 0, 0, 1, std::numeric_limits<float>::quiet_NaN(), 0, 0, 1, 0}, "VEC3", 3);
  return doc.gltf();
}
Bytes accessor_index_out_of_range() {
  return edit([](json& d) { d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9; });
}
Bytes sparse_indices_out_of_range() {
  Doc doc = triangle();
  Bytes indices, values;
  put<uint16_t>(indices, 7);  // the accessor has 3 elements
  put<uint16_t>(indices, 0);
  for (float v : {0.0f, 0.0f, 1.0f}) put<float>(values, v);
  const int index_view = doc.view(indices), value_view = doc.view(values);
  doc.root["accessors"][0]["sparse"] = {
      {"count", 1}, {"indices", {{"bufferView", index_view}, {"componentType", 5123}}}, {"values", {{"bufferView", value_view}}}};
  return doc.gltf();
}
Bytes morph_target_counts_differ() {
  Doc doc = triangle();
  doc.primitive()["targets"] = {{{"POSITION", doc.floats({0, 0, 1, 0, 0, 1}, "VEC3", 3)}}};
  doc.root["accessors"].back()["min"] = {0, 0, 1};  // so that the counts are its only error
  doc.root["accessors"].back()["max"] = {0, 0, 1};
  return doc.gltf();
}
Bytes mode_out_of_range() {
  return edit([](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 7; });
}

// --- Indices into other arrays -----------------------------------------------------------------------

Bytes scene_out_of_range() {
  return edit([](json& d) { d["scene"] = 5; });
}
Bytes scene_node_out_of_range() {
  return edit([](json& d) { d["scenes"][0]["nodes"] = {3}; });
}
Bytes mesh_out_of_range() {
  return edit([](json& d) { d["nodes"][0]["mesh"] = 2; });
}
Bytes with_texture(void (*change)(json&)) {
  Doc doc = textured();
  doc.image(png(2, 2, 3), "image/png");
  doc.root["samplers"] = {{{"magFilter", 9729}}};
  doc.root["textures"][0]["sampler"] = 0;
  json out = doc.finished();
  change(out);
  return out.dump();
}
Bytes sampler_out_of_range() {
  return with_texture([](json& d) { d["textures"][0]["sampler"] = 4; });
}
Bytes texture_source_out_of_range() {
  return with_texture([](json& d) { d["textures"][0]["source"] = 3; });
}
Bytes material_texture_out_of_range() {
  return with_texture([](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 2; });
}
Bytes image_buffer_view_out_of_range() {
  return with_texture([](json& d) { d["images"][0] = {{"bufferView", 9}, {"mimeType", "image/png"}}; });
}
Bytes sampler_filter_invalid() {
  return with_texture([](json& d) { d["samplers"][0]["magFilter"] = 1234; });
}
Bytes material_out_of_range() {
  return edit([](json& d) { d["meshes"][0]["primitives"][0]["material"] = 0; });
}

// --- The node hierarchy ------------------------------------------------------------------------------

Bytes node_cycle() {
  return edit([](json& d) { d["nodes"] = {{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}}; });
}
Bytes node_self_child() {
  return edit([](json& d) { d["nodes"][0]["children"] = {0}; });
}
Bytes node_two_parents() {
  return edit([](json& d) {
    d["nodes"] = {{{"children", {2}}}, {{"children", {2}}}, {{"mesh", 0}}};
    d["scenes"][0]["nodes"] = {0, 1};
  });
}
Bytes node_chain_cycle() {
  // The 100,000-deep chain whose last node points back at the first: the cycle is found without recursion.
  Bytes text = valid_node_chain();
  const Bytes last = "\"mesh\":0";
  return text.replace(text.rfind(last), last.size(), "\"children\":[0],\"mesh\":0");
}
Bytes node_matrix_not_finite() {
  // JSON has no infinity; 1e400 is the way a file spells it, and a parser reads it as inf.
  Bytes text = edit([](json& d) { d["nodes"][0]["scale"] = {2, 2, 2}; });
  return text.replace(text.find("[2,2,2]"), 7, "[1e400,1,1]");
}

// --- Scenes and primitives with nothing to draw --------------------------------------------------------

Bytes points_only() {
  return edit([](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 0; });
}
Bytes no_scenes() {
  return edit([](json& d) {
    d.erase("scene");
    d.erase("scenes");
  });
}
Bytes empty_scene() {
  return edit([](json& d) { d["scenes"][0]["nodes"] = json::array(); });
}
Bytes no_position() {
  return edit([](json& d) { d["meshes"][0]["primitives"][0]["attributes"] = {{"NORMAL", 0}}; });
}
Bytes required_extension() {
  return edit([](json& d) {
    d["extensionsUsed"] = {"KHR_texture_basisu"};
    d["extensionsRequired"] = {"KHR_texture_basisu"};
  });
}
Bytes uri_escapes() {
  return edit([](json& d) { d["buffers"][0]["uri"] = "../outside.bin"; });
}
Bytes not_json() {
  return "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ ";
}
Bytes top_level_array() {
  return "[]";
}

// --- Textures that cannot be used ----------------------------------------------------------------------

Bytes png_65535() {
  return valid_texture(png(1, 1, 3, 65535, 65535), "image/png");
}
Bytes png_garbage() {
  Bytes bytes = png(4, 4, 3);
  for (size_t i = 16; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 37 + 11) & 0xFF);
  return valid_texture(bytes, "image/png");
}
Bytes jpeg_truncated() {
  return valid_texture(jpeg().substr(0, sizeof kJpeg / 2), "image/jpeg");
}
Bytes image_not_png_or_jpeg() {
  return valid_texture("GIF89a\x01\x00\x01\x00", "image/png");
}

// --- GLB layout ----------------------------------------------------------------------------------------

Bytes patched(Bytes glb, size_t at, uint32_t value) {
  std::memcpy(&glb[at], &value, 4);
  return glb;
}
Bytes glb_header_only() {
  return triangle().glb().substr(0, 8);
}
Bytes glb_bad_magic() {
  return "gltf" + triangle().glb().substr(4);
}
Bytes glb_version_1() {
  return patched(triangle().glb(), 4, 1);
}
Bytes glb_length_mismatch() {
  return patched(triangle().glb(), 8, 4096);
}
Bytes glb_json_chunk_past_end() {
  const Bytes glb = triangle().glb();
  return patched(glb, 12, static_cast<uint32_t>(glb.size()));
}
Bytes glb_bin_chunk_past_end() {
  const Bytes glb = triangle().glb();
  uint32_t json_length = 0;
  std::memcpy(&json_length, &glb[12], 4);
  return patched(glb, 20 + json_length, 0x10000);
}
Bytes glb_first_chunk_bin() {
  return patched(triangle().glb(), 16, 0x004E4942);
}
Bytes glb_two_json_chunks() {
  const Bytes glb = triangle().glb();
  uint32_t json_length = 0;
  std::memcpy(&json_length, &glb[12], 4);
  return patched(glb, 20 + json_length + 4, 0x4E4F534A);
}
Bytes glb_truncated() {
  Bytes glb = triangle().glb();
  glb.resize(glb.size() - 8);
  return patched(glb, 8, static_cast<uint32_t>(glb.size()));
}

const std::vector<Case> kCases = {
    // Valid: each must load.
    {"valid-triangle.gltf", true, valid_triangle},
    {"valid-triangle.glb", true, valid_triangle_glb},
    {"valid-no-indices.gltf", true, valid_no_indices},
    {"valid-u8-indices.gltf", true, valid_u8_indices},
    {"valid-u32-indices.gltf", true, valid_u32_indices},
    {"valid-triangle-strip.gltf", true, valid_strip},
    {"valid-triangle-fan.gltf", true, valid_fan},
    {"valid-normals.gltf", true, valid_normals},
    {"valid-texcoords.gltf", true, valid_texcoords},
    {"valid-texcoords-normalized-ushort.gltf", true, valid_texcoords_ushort},
    {"valid-interleaved-stride-24.gltf", true, valid_interleaved_24},
    {"valid-stride-252.gltf", true, valid_stride_252},
    {"valid-texture-png-rgb.gltf", true, valid_png_rgb},
    {"valid-texture-png-grey.gltf", true, valid_png_grey},
    {"valid-texture-png-rgba.gltf", true, valid_png_rgba},
    {"valid-texture-jpeg.gltf", true, valid_jpeg},
    {"valid-image-in-bufferview.glb", true, valid_image_in_glb},
    {"valid-node-trs.gltf", true, valid_trs},
    {"valid-node-matrix.gltf", true, valid_matrix},
    {"valid-two-scenes.gltf", true, valid_two_scenes},
    {"valid-lines-and-triangles.gltf", true, valid_lines_and_triangles},
    {"valid-version-2.1.gltf", true, valid_version_2_1},
    {"valid-min-version-2.0.gltf", true, valid_min_version},
    {"valid-morph-target.gltf", true, valid_morph_target},
    {"valid-glb-json-chunk-only.glb", true, valid_glb_json_only},
    {"valid-extras-nested-100.gltf", true, valid_nested_extras},
    {"valid-unicode-names.gltf", true, valid_unicode_names},
    {"valid-node-chain-100000.gltf", true, valid_node_chain},
    {"valid-5000-nodes-share-a-mesh.gltf", true, valid_shared_mesh},
    {"valid-two-primitives.gltf", true, valid_two_primitives},
    {"valid-camera-node.gltf", true, valid_points_and_camera},
    {"valid-extensions-used.gltf", true, valid_extensions_used},
    {"valid-glb-unknown-chunk.glb", true, valid_glb_unknown_chunk},
    // Valid glTF the player deliberately treats differently (see the unit tests for the verdicts).
    {"points-only.gltf", true, points_only},
    {"no-scenes.gltf", true, no_scenes},
    {"empty-scene.gltf", false, empty_scene},
    // Invalid: the named defects.
    {"empty.glb", false, empty_glb},
    {"negative-byteoffset.gltf", false, negative_byte_offset},
    {"version-1.0.gltf", false, version_1},
    {"min-version-2.1.gltf", true, min_version_2_1},
    {"version-missing.gltf", false, version_missing},
    {"json-nested-200000.gltf", true, json_nested_200000},
    {"json-nested-200000.glb", true, json_nested_200000_glb},
    {"utf8-bom.gltf", false, valid_bom},
    // Accessors and buffer views.
    {"stride-below-element.gltf", false, stride_below_element},
    {"stride-above-252.gltf", false, stride_above_252},
    {"stride-not-multiple-of-4.gltf", false, stride_not_multiple_of_4},
    {"position-type-vec2.gltf", false, position_vec2},
    {"position-componenttype-ushort.gltf", false, position_ushort},
    {"indices-type-vec2.gltf", false, indices_vec2},
    {"indices-float.gltf", false, float_indices},
    {"attribute-counts-differ.gltf", false, attribute_counts_differ},
    {"unread-attribute-count-differs.gltf", false, unread_attribute_count_differs},
    {"count-beyond-2^64.gltf", false, count_beyond_2_64},
    {"accessor-offset-beyond-2^64.gltf", false, offset_beyond_2_64},
    {"bufferview-offset-beyond-2^64.gltf", false, view_offset_beyond_2_64},
    {"count-times-size-overflows.gltf", false, count_product_overflows},
    {"count-above-limit.gltf", false, count_above_limit},
    {"count-float.gltf", false, count_float},
    {"count-string.gltf", false, count_string},
    {"count-zero.gltf", false, count_zero},
    {"accessor-beyond-bufferview.gltf", false, accessor_beyond_view},
    {"bufferview-beyond-buffer.gltf", false, view_beyond_buffer},
    {"accessor-unaligned.gltf", false, accessor_unaligned},
    {"index-beyond-vertex-count.gltf", false, index_beyond_vertices},
    {"position-nan.gltf", false, nan_position},
    {"accessor-index-out-of-range.gltf", false, accessor_index_out_of_range},
    {"sparse-indices-out-of-range.gltf", false, sparse_indices_out_of_range},
    {"morph-target-counts-differ.gltf", false, morph_target_counts_differ},
    {"mode-out-of-range.gltf", false, mode_out_of_range},
    // Indices into other arrays.
    {"scene-out-of-range.gltf", false, scene_out_of_range},
    {"scene-node-out-of-range.gltf", false, scene_node_out_of_range},
    {"node-mesh-out-of-range.gltf", false, mesh_out_of_range},
    {"sampler-out-of-range.gltf", false, sampler_out_of_range},
    {"texture-source-out-of-range.gltf", false, texture_source_out_of_range},
    {"material-texture-out-of-range.gltf", false, material_texture_out_of_range},
    {"image-bufferview-out-of-range.gltf", false, image_buffer_view_out_of_range},
    {"sampler-filter-invalid.gltf", true, sampler_filter_invalid},  // the validator warns: the default filter
    {"material-out-of-range.gltf", false, material_out_of_range},
    // The node hierarchy.
    {"node-cycle.gltf", false, node_cycle},
    {"node-own-child.gltf", false, node_self_child},
    {"node-two-parents.gltf", false, node_two_parents},
    {"node-chain-100000-cycle.gltf", false, node_chain_cycle},
    {"node-scale-infinite.gltf", false, node_matrix_not_finite},
    // Other structure.
    {"primitive-without-position.gltf", false, no_position},
    {"required-extension.gltf", true, required_extension},
    {"uri-escapes-folder.gltf", false, uri_escapes},
    {"not-json.gltf", false, not_json},
    {"top-level-array.gltf", false, top_level_array},
    // Textures that cannot be used.
    {"texture-png-65535x65535.gltf", true, png_65535},
    {"texture-png-garbage.gltf", false, png_garbage},
    {"texture-jpeg-truncated.gltf", true, jpeg_truncated},
    {"texture-not-png-or-jpeg.gltf", false, image_not_png_or_jpeg},
    // GLB layout.
    {"glb-header-only.glb", false, glb_header_only},
    {"glb-bad-magic.glb", false, glb_bad_magic},
    {"glb-version-1.glb", false, glb_version_1},
    {"glb-length-mismatch.glb", false, glb_length_mismatch},
    {"glb-json-chunk-past-end.glb", false, glb_json_chunk_past_end},
    {"glb-bin-chunk-past-end.glb", false, glb_bin_chunk_past_end},
    {"glb-first-chunk-bin.glb", false, glb_first_chunk_bin},
    {"glb-two-json-chunks.glb", false, glb_two_json_chunks},
    {"glb-truncated-bin.glb", false, glb_truncated},
};

}  // namespace

const std::vector<Case>& cases() {
  return kCases;
}

std::string bytes_of(const std::string& name) {
  for (const Case& c : kCases)
    if (c.name == name) return c.make();
  throw std::out_of_range("gltf corpus: no case named '" + name + "'");
}

size_t write_all(const std::string& dir) {
  size_t written = 0;
  for (const Case& c : kCases) {
    std::ofstream out(dir + "/" + c.name, std::ios::binary);
    const std::string bytes = c.make();
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (out) ++written;
  }
  return written;
}

}  // namespace corpus
