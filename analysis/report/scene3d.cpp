#include "analysis/report/scene3d.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace kneesim::report {
namespace {

nlohmann::json mesh_json(const SceneMesh& m) {
  std::vector<float> p;
  p.reserve(3 * m.vertices_mm.size());
  for (const auto& v : m.vertices_mm) {
    for (int k = 0; k < 3; ++k) p.push_back(static_cast<float>(v[k]));
  }
  std::vector<uint32_t> t;
  t.reserve(3 * m.triangles.size());
  for (const auto& f : m.triangles) {
    for (int k = 0; k < 3; ++k) t.push_back(static_cast<uint32_t>(f[k]));
  }
  return {{"positions", base64(p.data(), p.size() * sizeof(float))},
          {"triangles", base64(t.data(), t.size() * sizeof(uint32_t))},
          {"vertices", m.vertices_mm.size()},
          {"faces", m.triangles.size()}};
}

}  // namespace

std::string base64(const void* data, size_t bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* b = static_cast<const unsigned char*>(data);
  std::string o;
  o.reserve((bytes + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes; i += 3) {
    const uint32_t v = (b[i] << 16) | (b[i + 1] << 8) | b[i + 2];
    o += k[v >> 18];
    o += k[(v >> 12) & 63];
    o += k[(v >> 6) & 63];
    o += k[v & 63];
  }
  if (i + 1 == bytes) {
    const uint32_t v = b[i] << 16;
    o += k[v >> 18];
    o += k[(v >> 12) & 63];
    o += "==";
  } else if (i + 2 == bytes) {
    const uint32_t v = (b[i] << 16) | (b[i + 1] << 8);
    o += k[v >> 18];
    o += k[(v >> 12) & 63];
    o += k[(v >> 6) & 63];
    o += '=';
  }
  return o;
}

nlohmann::json scene_json(const Scene3D& s) {
  nlohmann::json j;
  j["insert"] = mesh_json(s.insert);
  if (!s.femur.empty()) {
    j["femur"] = mesh_json(s.femur);
    std::vector<float> poses;
    for (const auto& X : s.femur_pose_mm) {
      const Eigen::Matrix4d m = X.matrix();
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) poses.push_back(static_cast<float>(m(r, c)));
      }
    }
    j["femur_poses"] = base64(poses.data(), poses.size() * sizeof(float));
    j["femur_pose_count"] = s.femur_pose_mm.size();
  }
  j["step_name"] = s.step_name;
  j["step_unit"] = s.step_unit;
  j["step_values"] = s.step_values;
  j["initial_step"] = std::clamp(s.initial_step, 0, std::max(0, int(s.step_values.size()) - 1));
  j["note"] = s.note;
  nlohmann::json fields = nlohmann::json::array();
  const size_t faces = s.insert.triangles.size();
  for (const SceneField& f : s.fields) {
    if (f.steps.size() != s.step_values.size()) {
      throw std::logic_error("report scene: field '" + f.name + "' has " +
                             std::to_string(f.steps.size()) + " steps, the slider " +
                             std::to_string(s.step_values.size()));
    }
    double lo = 0.0, hi = 0.0;
    bool any = false;
    for (const auto& step : f.steps) {
      if (step.size() != faces) {
        throw std::logic_error("report scene: field '" + f.name + "' has " +
                               std::to_string(step.size()) + " values for " +
                               std::to_string(faces) + " insert faces");
      }
      for (double v : step) {
        if (!std::isfinite(v)) continue;
        lo = any ? std::min(lo, v) : v;
        hi = any ? std::max(hi, v) : v;
        any = true;
      }
    }
    lo = std::min(lo, 0.0);  // the colour scale starts at zero (no pressure, no wear)
    // faces with a value at some step (the articular surface); the others are not stored
    std::vector<uint32_t> subset;
    for (size_t i = 0; i < faces; ++i) {
      bool has = false;
      for (const auto& step : f.steps) has = has || std::isfinite(step[i]);
      if (has) subset.push_back(static_cast<uint32_t>(i));
    }
    std::vector<uint8_t> q;
    q.reserve(subset.size() * f.steps.size());
    std::vector<double> step_max;
    for (const auto& step : f.steps) {
      double m = 0.0;
      for (uint32_t i : subset) {
        const double v = step[i];
        if (!std::isfinite(v)) {
          q.push_back(255);
          continue;
        }
        m = std::max(m, v);
        const double u = hi > lo ? (v - lo) / (hi - lo) : 0.0;
        q.push_back(static_cast<uint8_t>(std::lround(std::clamp(u, 0.0, 1.0) * 254.0)));
      }
      step_max.push_back(m);
    }
    fields.push_back({{"name", f.name},
                      {"unit", f.unit},
                      {"min", lo},
                      {"max", hi},
                      {"step_max", step_max},
                      {"faces", base64(subset.data(), subset.size() * sizeof(uint32_t))},
                      {"face_count", subset.size()},
                      {"values", base64(q.data(), q.size())}});
  }
  j["fields"] = fields;
  return j;
}

}  // namespace kneesim::report
