#include "env/mujoco_model.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace vaegail {

namespace {
// MuJoCo's message spans lines ("Error: ...\nObject name = ..."): keep the error one line.
std::string one_line(std::string message) {
  while (!message.empty() && message.back() == '\n') message.pop_back();
  for (size_t at = 0; (at = message.find('\n', at)) != std::string::npos;) message.replace(at, 1, "; ");
  return message;
}
}  // namespace

std::shared_ptr<const MujocoModel> MujocoModel::from_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot load MJCF model: no such file or not readable");
  std::ostringstream text;
  text << in.rdbuf();
  // Compiled from the file itself, so that includes and meshes resolve as MuJoCo resolves them.
  char error[1000] = "";
  mjModel* model = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
  if (!model) throw std::runtime_error(path + ": cannot load MJCF model: " + one_line(error));
  return std::shared_ptr<const MujocoModel>(new MujocoModel(model, path, text.str()));
}

std::shared_ptr<const MujocoModel> MujocoModel::from_xml(const std::string& name,
                                                         const std::string& xml) {
  // mjVFS holds thousands of file slots: keep it off the stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), name.c_str(), static_cast<int>(xml.size())) != 0)
    throw std::runtime_error(name + ": cannot stage embedded model");
  std::copy(xml.begin(), xml.end(), static_cast<char*>(vfs->filedata[vfs->nfile - 1]));
  char error[1000] = "";
  mjModel* model = mj_loadXML(name.c_str(), vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!model) throw std::runtime_error(name + ": cannot load MJCF model: " + one_line(error));
  return std::shared_ptr<const MujocoModel>(new MujocoModel(model, name, xml));
}

MujocoModel::~MujocoModel() { mj_deleteModel(model_); }

int MujocoModel::id(mjtObj type, const std::string& name) const {
  const int i = mj_name2id(model_, type, name.c_str());
  if (i < 0) throw std::runtime_error(source_ + ": model has no object named '" + name + "'");
  return i;
}

}  // namespace vaegail
