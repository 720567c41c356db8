// SPDX-License-Identifier: GPL-3.0-or-later
// 3D previews: binary STL (millimetres, as slicers assume) and glTF 2.0 through tinygltf (metres,
// +Y up, as the specification requires). The model's 3D frame is taken as +Z up (docs/export.md),
// so glTF gets (x, z, -y) / 1000, a rotation that keeps the triangles' winding.
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "internal.h"

namespace dform::fab {

namespace {

constexpr int kArrayBuffer = 34962;         // glTF bufferView target for vertex attributes
constexpr int kElementArrayBuffer = 34963;  // glTF bufferView target for indices

template <typename T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

Eigen::Vector3d faceNormal(const Points3& V, const Eigen::Vector3i& f) {
  const Eigen::Vector3d a = V.row(f[0]), b = V.row(f[1]), c = V.row(f[2]);
  const Eigen::Vector3d n = (b - a).cross(c - a);
  return n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
}

// Model frame (mm, +Z up) to glTF (m, +Y up).
Eigen::Vector3d toGltf(const Eigen::Vector3d& p) {
  return Eigen::Vector3d(p.x(), p.z(), -p.y()) / 1000.0;
}

// sRGB component to linear (glTF COLOR_0 is linear).
double srgbToLinear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// The curvature colour scale's floor (radians of angle defect, as validate's curvatureMap).
constexpr double kMinCurvatureScale = 1e-3;

// Diverging blue-white-red map for t in [-1, 1], linear RGB.
Eigen::Vector3f curvatureColor(double t) {
  t = std::clamp(t, -1.0, 1.0);
  const Eigen::Vector3d white(0.97, 0.97, 0.97), blue(0.23, 0.30, 0.75), red(0.71, 0.02, 0.15);
  const Eigen::Vector3d srgb = t < 0 ? Eigen::Vector3d(white + (-t) * (blue - white))
                                     : Eigen::Vector3d(white + t * (red - white));
  return Eigen::Vector3f(float(srgbToLinear(srgb.x())), float(srgbToLinear(srgb.y())),
                         float(srgbToLinear(srgb.z())));
}

class GltfBuilder {
 public:
  GltfBuilder() { model_.buffers.resize(1); }

  // Appends raw bytes as a bufferView (4-byte aligned) and returns its index.
  int view(const void* data, size_t bytes, int target) {
    auto& buf = model_.buffers[0].data;
    while (buf.size() % 4 != 0) buf.push_back(0);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = buf.size();
    v.byteLength = bytes;
    v.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buf.insert(buf.end(), p, p + bytes);
    model_.bufferViews.push_back(v);
    return int(model_.bufferViews.size()) - 1;
  }

  int vec3(const std::vector<Eigen::Vector3f>& values, bool withBounds) {
    tinygltf::Accessor a;
    a.bufferView = view(values.data(), values.size() * sizeof(Eigen::Vector3f), kArrayBuffer);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = TINYGLTF_TYPE_VEC3;
    a.count = values.size();
    if (withBounds) {  // from the stored floats, so that the validator finds them exact
      Eigen::Vector3f lo = values[0], hi = values[0];
      for (const auto& v : values) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      a.minValues = {lo.x(), lo.y(), lo.z()};
      a.maxValues = {hi.x(), hi.y(), hi.z()};
    }
    model_.accessors.push_back(a);
    return int(model_.accessors.size()) - 1;
  }

  int indices(const std::vector<uint32_t>& values) {
    tinygltf::Accessor a;
    a.bufferView = view(values.data(), values.size() * sizeof(uint32_t), kElementArrayBuffer);
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.type = TINYGLTF_TYPE_SCALAR;
    a.count = values.size();
    model_.accessors.push_back(a);
    return int(model_.accessors.size()) - 1;
  }

  int material(const std::string& name, const Eigen::Vector4d& color, bool unlit) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = {color[0], color[1], color[2], color[3]};
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    m.pbrMetallicRoughness.roughnessFactor = 0.8;
    m.doubleSided = true;  // open sheets are seen from both sides
    if (unlit) m.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
    model_.materials.push_back(m);
    return int(model_.materials.size()) - 1;
  }

  void node(const std::string& name, const tinygltf::Primitive& primitive) {
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(primitive);
    model_.meshes.push_back(mesh);
    tinygltf::Node n;
    n.name = name;
    n.mesh = int(model_.meshes.size()) - 1;
    model_.nodes.push_back(n);
  }

  tinygltf::Model& model() { return model_; }

 private:
  tinygltf::Model model_;
};

}  // namespace

std::string stlDocument(const DForm& model, bool failedGate) {
  std::string out;
  std::string header = "dform binary STL, millimetres, pieces A and B";
  if (failedGate) header += " - FAILED GATE";
  header.resize(80, ' ');  // must not start with "solid" (that marks ASCII STL)
  out += header;
  const uint32_t count = uint32_t(model.a.F.rows() + model.b.F.rows());
  put(out, count);
  out.reserve(84 + 50 * size_t(count));
  for (const Piece* p : {&model.a, &model.b}) {
    for (Eigen::Index i = 0; i < p->F.rows(); ++i) {
      const Eigen::Vector3i f = p->F.row(i);
      const Eigen::Vector3d n = faceNormal(p->shape, f);
      for (int k = 0; k < 3; ++k) put(out, float(n[k]));
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) put(out, float(p->shape(f[c], k)));
      put(out, uint16_t(0));
    }
  }
  return out;
}

Result<std::string> gltfDocument(const DForm& model, const ExportOptions& o) {
  const bool colored = !o.curvatureA.empty() || !o.curvatureB.empty();
  if (colored && (o.curvatureA.size() != size_t(model.a.shape.rows()) ||
                  o.curvatureB.size() != size_t(model.b.shape.rows()))) {
    return Status{ErrorCode::Usage, "curvature colours need one value per vertex of each piece (" +
                                        std::to_string(model.a.shape.rows()) + " and " +
                                        std::to_string(model.b.shape.rows()) + ")"};
  }
  // Colour scale: the largest |K| over both pieces, never below 1e-3 (in validate's unit,
  // radians: rounding noise on an exactly developable shape stays white), the scale of
  // report.html's curvature maps (report/views.cpp, curvatureScale), so that a colour means the
  // same in both.
  double scale = kMinCurvatureScale;
  for (const std::vector<double>* values : {&o.curvatureA, &o.curvatureB})
    for (double k : *values)
      if (std::isfinite(k)) scale = std::max(scale, std::abs(k));
  GltfBuilder g;
  const std::string tag = o.failedGateMark ? " (FAILED GATE)" : "";
  // Each piece its own base colour, so that A and B tell apart in any viewer; under a curvature
  // map (COLOR_0, which glTF multiplies by the base colour) a light tint of it, so the map's
  // white, blue and red still read.
  const Eigen::Vector4d colors[2] = {{0.80, 0.45, 0.20, 1.0}, {0.20, 0.45, 0.80, 1.0}};
  const Eigen::Vector4d tints[2] = {{1.00, 0.90, 0.80, 1.0}, {0.80, 0.90, 1.00, 1.0}};
  const Piece* pieces[2] = {&model.a, &model.b};
  const std::vector<double>* curvature[2] = {&o.curvatureA, &o.curvatureB};
  for (int p = 0; p < 2; ++p) {
    const Piece& piece = *pieces[p];
    const std::string name = (piece.name.empty() ? (p == 0 ? "A" : "B") : piece.name) + tag;
    const Eigen::Index nv = piece.shape.rows();
    std::vector<Eigen::Vector3f> pos(static_cast<size_t>(nv)), nrm(static_cast<size_t>(nv)), col;
    std::vector<Eigen::Vector3d> acc(size_t(nv), Eigen::Vector3d::Zero());
    std::vector<uint32_t> idx;
    for (Eigen::Index i = 0; i < piece.F.rows(); ++i) {
      const Eigen::Vector3i f = piece.F.row(i);
      const Eigen::Vector3d a = piece.shape.row(f[0]), b = piece.shape.row(f[1]),
                            c = piece.shape.row(f[2]);
      const Eigen::Vector3d areaNormal = (b - a).cross(c - a);  // area-weighted
      for (int k = 0; k < 3; ++k) {
        acc[size_t(f[k])] += areaNormal;
        idx.push_back(uint32_t(f[k]));
      }
    }
    for (Eigen::Index v = 0; v < nv; ++v) {
      pos[size_t(v)] = toGltf(piece.shape.row(v).transpose()).cast<float>();
      const Eigen::Vector3d n = toGltf(acc[size_t(v)]);
      nrm[size_t(v)] = n.norm() > 0 ? n.normalized().cast<float>() : Eigen::Vector3f(0, 1, 0);
      if (colored) col.push_back(curvatureColor((*curvature[p])[size_t(v)] / scale));
    }
    if (nv == 0 || idx.empty())
      return Status{ErrorCode::InputInvalid, "piece " + name + " has no triangles"};
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = g.vec3(pos, true);
    prim.attributes["NORMAL"] = g.vec3(nrm, false);
    if (colored) prim.attributes["COLOR_0"] = g.vec3(col, false);
    prim.indices = g.indices(idx);
    prim.material = g.material(name, colored ? tints[p] : colors[p], false);
    g.node(name, prim);
  }
  {  // The seam as a line loop drawn with LINES (piece A's side of each seam pair).
    std::vector<Eigen::Vector3f> pos;
    for (int v : model.a.seam)
      pos.push_back(toGltf(model.a.shape.row(v).transpose()).cast<float>());
    std::vector<uint32_t> idx;
    for (size_t i = 0; i < pos.size(); ++i) {
      const size_t j = (i + 1) % pos.size();
      if ((pos[i] - pos[j]).norm() > 0) {  // degenerate lines should not occur
        idx.push_back(uint32_t(i));
        idx.push_back(uint32_t(j));
      }
    }
    if (!idx.empty()) {
      tinygltf::Primitive prim;
      prim.mode = TINYGLTF_MODE_LINE;
      prim.attributes["POSITION"] = g.vec3(pos, true);
      prim.indices = g.indices(idx);
      prim.material = g.material("seam", {0.05, 0.05, 0.05, 1.0}, true);
      g.node("seam" + tag, prim);
    }
  }
  tinygltf::Model& m = g.model();
  m.extensionsUsed.push_back("KHR_materials_unlit");
  m.asset.version = "2.0";
  m.asset.generator = "dform export";
  tinygltf::Value::Object extras;
  extras["job"] = tinygltf::Value(o.jobName);
  extras["units"] = tinygltf::Value(std::string("metres (model in mm / 1000), +Y up"));
  extras["failedGate"] = tinygltf::Value(o.failedGateMark);
  // |curvature| that maps to full red or blue, in the unit of the values given.
  if (colored) extras["curvatureColourScale"] = tinygltf::Value(scale);
  m.asset.extras = tinygltf::Value(extras);
  tinygltf::Scene scene;
  scene.name = o.jobName + tag;
  for (size_t i = 0; i < m.nodes.size(); ++i) scene.nodes.push_back(int(i));
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  std::ostringstream stream;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&m, stream, !o.gltfBinary, o.gltfBinary))
    return Status{ErrorCode::OutputFailed, "glTF: tinygltf could not serialise the model"};
  return stream.str();
}

}  // namespace dform::fab
