// SPDX-License-Identifier: GPL-3.0-or-later
// 3D previews read back: binary STL (count, size, bounding box, outward normals) and glTF
// (tinygltf load: meshes, units, +Y up; the Khronos validator when node has it).
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <cstring>
#include <filesystem>

#include "dform/export/exporter.h"
#include "dform/validate/metrics.h"
#include "synthetic.h"
#include "test_util.h"

namespace dform::test {
namespace {

namespace fs = std::filesystem;

ExportOptions meshOptions() {
  ExportOptions o;
  o.templatesDir = DFORM_TEMPLATES_DIR;
  o.jobName = "mesh-test";
  return o;
}

std::string exportModel(const std::string& name, const DForm& model, const ExportOptions& o) {
  const std::string dir = freshDir(name);
  auto r = exportAll(model, o, dir);
  EXPECT_TRUE(r.isOk()) << r.status().message();
  return dir;
}

template <typename T>
T get(const std::string& s, size_t at) {
  T v;
  std::memcpy(&v, s.data() + at, sizeof(T));
  return v;
}

TEST(ExportMesh, StlHasEveryTriangleOutwardInMillimetres) {
  const DForm model = ellipseCircleDForm();
  const std::string stl = readText(exportModel("stl", model, meshOptions()) + "/dform.stl");
  const uint32_t n = get<uint32_t>(stl, 80);
  EXPECT_EQ(n, uint32_t(model.a.F.rows() + model.b.F.rows()));
  EXPECT_EQ(stl.size(), 84 + 50 * size_t(n));
  EXPECT_NE(stl.substr(0, 5), "solid") << "a binary STL must not look like ASCII STL";
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  double volume = 0;  // divergence theorem: positive when the normals point outward
  for (uint32_t i = 0; i < n; ++i) {
    const size_t at = 84 + 50 * size_t(i);
    Eigen::Vector3d normal, v[3];
    for (int k = 0; k < 3; ++k) normal[k] = get<float>(stl, at + 4 * size_t(k));
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k)
        v[c][k] = get<float>(stl, at + 12 + 12 * size_t(c) + 4 * size_t(k));
    const Eigen::Vector3d cross = (v[1] - v[0]).cross(v[2] - v[0]);
    EXPECT_GT(normal.dot(cross.normalized()), 0.999) << "normal follows the right-hand rule";
    volume += v[0].dot(v[1].cross(v[2])) / 6;
    for (const auto& p : v) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  EXPECT_GT(volume, 0);
  Eigen::Vector3d mlo =
      model.a.shape.colwise().minCoeff().cwiseMin(model.b.shape.colwise().minCoeff());
  Eigen::Vector3d mhi =
      model.a.shape.colwise().maxCoeff().cwiseMax(model.b.shape.colwise().maxCoeff());
  EXPECT_LT((lo - mlo).norm(), 1e-4);  // float precision at 100 mm
  EXPECT_LT((hi - mhi).norm(), 1e-4);
}

TEST(ExportMesh, GltfHasBothPiecesTheSeamAndMetresYUp) {
  const DForm model = ellipseCircleDForm();
  ExportOptions o = meshOptions();
  o.curvatureA = fakeCurvature(model.a);
  o.curvatureB = fakeCurvature(model.b);
  const std::string dir = exportModel("gltf", model, o);
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, dir + "/dform.glb")) << err;
  ASSERT_EQ(m.meshes.size(), 3u);
  EXPECT_EQ(m.materials.size(), 3u);
  for (int p = 0; p < 2; ++p) {
    const auto& prim = m.meshes[size_t(p)].primitives.at(0);
    EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
    EXPECT_EQ(m.accessors[size_t(prim.indices)].count, size_t(3 * model.a.F.rows()));
    EXPECT_TRUE(prim.attributes.count("NORMAL"));
    EXPECT_TRUE(prim.attributes.count("COLOR_0"));
    EXPECT_NE(prim.material, m.meshes[size_t(1 - p)].primitives.at(0).material) << "own materials";
  }
  // Each piece its own base colour.
  EXPECT_NE(m.materials[0].pbrMetallicRoughness.baseColorFactor,
            m.materials[1].pbrMetallicRoughness.baseColorFactor);
  const auto& seam = m.meshes[2].primitives.at(0);
  EXPECT_EQ(seam.mode, TINYGLTF_MODE_LINE);
  EXPECT_EQ(m.accessors[size_t(seam.indices)].count, 2 * model.a.seam.size());
  // +Y up and metres: glTF y spans the model's z range / 1000.
  const auto& posA = m.accessors[size_t(m.meshes[0].primitives[0].attributes.at("POSITION"))];
  EXPECT_NEAR(posA.maxValues[1], model.a.shape.col(2).maxCoeff() / 1000, 1e-6);
  EXPECT_NEAR(posA.maxValues[0], model.a.shape.col(0).maxCoeff() / 1000, 1e-6);
  EXPECT_NEAR(posA.minValues[2], -model.a.shape.col(1).maxCoeff() / 1000, 1e-6);
}

void validate(const std::string& file, int triangles) {
  const std::string node = DFORM_NODE, modules = DFORM_NODE_PATH;
  if (node.empty() || !fs::exists(modules + "/gltf-validator"))
    GTEST_SKIP()
        << "node or the gltf-validator npm package is not available (the build installs it "
           "into build/node when npm can reach the registry)";
  std::string out;
  const int rc = run(
      "NODE_PATH='" + modules + "' '" + node + "' '" DFORM_GLTF_VALIDATE_SCRIPT "' '" + file + "'",
      &out);
  EXPECT_EQ(rc, 0) << out;
  // Clean, not only valid: no error, no warning, no info (hints are style advice).
  for (const char* count : {"\"numErrors\": 0,", "\"numWarnings\": 0,", "\"numInfos\": 0,"})
    EXPECT_NE(out.find(count), std::string::npos) << count << "\n" << out;
  EXPECT_NE(out.find("\"totalTriangleCount\": " + std::to_string(triangles)), std::string::npos)
      << out;
}

// The curvature colours the command line exports: validate's curvature map of each piece.
void colourByCurvatureMap(const DForm& model, ExportOptions& o) {
  const Eigen::VectorXd a = curvatureMap(model.a), b = curvatureMap(model.b);
  o.curvatureA.assign(a.data(), a.data() + a.size());
  o.curvatureB.assign(b.data(), b.data() + b.size());
}

TEST(ExportMesh, PiecesHaveTheirOwnColourAndTheCurvatureMapTheReportsScale) {
  const DForm model = ellipseCircleDForm();
  for (bool curvature : {false, true}) {
    ExportOptions o = meshOptions();
    if (curvature) colourByCurvatureMap(model, o);
    const std::string dir = exportModel(curvature ? "colours-map" : "colours", model, o);
    tinygltf::Model m;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, dir + "/dform.glb")) << err;
    const auto& a = m.materials[size_t(m.meshes[0].primitives[0].material)];
    const auto& b = m.materials[size_t(m.meshes[1].primitives[0].material)];
    EXPECT_NE(a.pbrMetallicRoughness.baseColorFactor, b.pbrMetallicRoughness.baseColorFactor)
        << (curvature ? "with" : "without") << " the curvature map";
    EXPECT_EQ(m.meshes[0].primitives[0].attributes.count("COLOR_0"), curvature ? 1u : 0u);
    if (!curvature) continue;
    // report.html's scale: the largest |angle defect| of either piece, at least 1e-3 rad.
    double top = 1e-3;
    for (const Piece* p : {&model.a, &model.b})
      top = std::max(top, curvatureMap(*p).cwiseAbs().maxCoeff());
    EXPECT_NEAR(m.asset.extras.Get("curvatureColourScale").GetNumberAsDouble(), top, 1e-12 * top);
  }
}

TEST(ExportMesh, GlbPassesTheKhronosValidator) {
  const DForm model = ellipseCircleDForm();
  ExportOptions o = meshOptions();
  colourByCurvatureMap(model, o);
  validate(exportModel("validate-glb", model, o) + "/dform.glb", int(2 * model.a.F.rows()));
}

TEST(ExportMesh, TextGltfPassesTheKhronosValidator) {
  ExportOptions o = meshOptions();
  o.gltfBinary = false;
  const DForm model = ellipseCircleDForm();
  colourByCurvatureMap(model, o);
  validate(exportModel("validate-gltf", model, o) + "/dform.gltf", int(2 * model.a.F.rows()));
}

TEST(ExportMesh, CurvatureOfTheWrongSizeIsAUsageError) {
  const DForm model = ellipseCircleDForm();
  ExportOptions o = meshOptions();
  o.curvatureA = {1.0, 2.0};
  o.curvatureB = fakeCurvature(model.b);
  auto r = exportAll(model, o, freshDir("bad-curvature"));
  ASSERT_FALSE(r.isOk());
  EXPECT_EQ(r.status().code(), ErrorCode::Usage);
}

}  // namespace
}  // namespace dform::test
