// A compiled MuJoCo model, shared read-only between the environments that step it.
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <string>

namespace vaegail {

class MujocoModel {
 public:
  // Throws std::runtime_error with MuJoCo's message and the file name on any error.
  static std::shared_ptr<const MujocoModel> from_file(const std::string& path);
  // `name` is used in messages and for relative includes; `xml` is the MJCF text.
  static std::shared_ptr<const MujocoModel> from_xml(const std::string& name, const std::string& xml);

  ~MujocoModel();
  MujocoModel(const MujocoModel&) = delete;
  MujocoModel& operator=(const MujocoModel&) = delete;

  const mjModel* get() const { return model_; }
  const std::string& source() const { return source_; }
  // The MJCF text the model was compiled from (the main file; <include>d files and meshes are
  // read from beside `source` and not part of it).
  const std::string& xml() const { return xml_; }
  // Index of a named object; throws naming the model and the object if it is missing.
  int id(mjtObj type, const std::string& name) const;

 private:
  MujocoModel(mjModel* model, std::string source, std::string xml)
      : model_(model), source_(std::move(source)), xml_(std::move(xml)) {}
  mjModel* model_;
  std::string source_, xml_;
};

// One mjData per environment.
struct MjDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using MjDataPtr = std::unique_ptr<mjData, MjDataDeleter>;

}  // namespace vaegail
