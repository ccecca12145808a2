#include "cli/figures.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "cli/embedded_plot_scripts.h"
#include "util/atomic_file.h"

extern char** environ;

namespace vaegail::cli {

namespace fs = std::filesystem;

namespace {

const char* kInstall = "needs python3 with matplotlib (apt-get install python3-matplotlib)";

struct Finished {
  int exit_code = -1;  // -1: could not start, or killed by a signal
  std::string err;     // what it wrote to stderr
};

// Runs argv[0] (looked up on PATH) with stdout inherited, or sent to /dev/null when `quiet`;
// stderr is captured.
Finished run_process(const std::vector<std::string>& argv, bool quiet) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) throw std::runtime_error("plot: cannot create a pipe");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[1]);
  if (quiet) posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::fflush(stdout);  // the child's output comes after ours
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_fds[1]);
  Finished done;
  char buf[4096];
  for (ssize_t n; (n = read(pipe_fds[0], buf, sizeof buf)) > 0;) done.err.append(buf, static_cast<size_t>(n));
  close(pipe_fds[0]);
  if (spawned != 0) return done;
  int status = 0;
  if (waitpid(pid, &status, 0) == pid && WIFEXITED(status)) done.exit_code = WEXITSTATUS(status);
  return done;
}

std::string find_python() {
  if (const char* chosen = std::getenv("VAEGAIL_PYTHON"))
    return run_process({chosen, "-c", "import matplotlib"}, true).exit_code == 0 ? chosen : "";
  for (const char* candidate : {"python3", "/usr/bin/python3"})
    if (run_process({candidate, "-c", "import matplotlib"}, true).exit_code == 0) return candidate;
  return "";
}

const std::string& python() {
  static const std::string found = find_python();
  return found;
}

// The script's one-line error ("curves.py: error: WHY", plotlib.run) without its prefix: WHY
// names the file and column itself.
std::string error_of(std::string text, const std::string& script) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  std::string line = text.substr(text.find_last_of('\n') + 1);
  const std::string prefix = script + ": error: ";
  return line.rfind(prefix, 0) == 0 ? line.substr(prefix.size()) : line;
}

// A fresh folder holding the script and the helper it imports; removed when done.
class ScriptFolder {
 public:
  explicit ScriptFolder(const std::string& script) {
    std::string pattern = (fs::temp_directory_path() / "vaegail-plot-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("plot: cannot create a folder under " + pattern);
    path_ = pattern;
    for (const std::string name : {std::string("plotlib.py"), script})
      write_file_atomically((path_ / name).string(), embedded_plot_script(name));
  }
  ~ScriptFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  std::string script(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

}  // namespace

bool plotting_available() { return !python().empty(); }

void require_plotting(const std::string& what) {
  if (!plotting_available()) throw std::runtime_error(what + ": " + kInstall);
}

void draw_figure(const std::string& script, const std::vector<std::string>& args) {
  require_plotting(script);
  const ScriptFolder folder(script);
  std::vector<std::string> argv{python(), folder.script(script)};
  argv.insert(argv.end(), args.begin(), args.end());
  const Finished done = run_process(argv, false);
  if (done.exit_code != 0) {
    const std::string why = error_of(done.err, script);
    throw std::runtime_error(why.empty() ? script + ": failed (exit " + std::to_string(done.exit_code) + ")" : why);
  }
  std::fputs(done.err.c_str(), stderr);  // matplotlib's warnings, if any
}

bool draw_figure_if_possible(const std::string& script, const std::vector<std::string>& args) {
  if (plotting_available()) {
    draw_figure(script, args);
    return true;
  }
  static bool warned = false;
  if (!warned)
    std::fprintf(stderr, "vaegail: warning: figures not drawn (their data is in the CSV beside each): %s\n", kInstall);
  warned = true;
  return false;
}

std::string figure_data_path(const std::string& figure) {
  return fs::path(figure).replace_extension(".csv").string();
}

bool save_histogram_figure(const std::string& figure, const std::vector<HistogramSeries>& series, int bins,
                           const FigureLabels& labels) {
  const std::string data = figure_data_path(figure);
  write_file_atomically(data, histogram_csv(series));
  return draw_figure_if_possible("histogram.py", {"--csv", data, "--column", "value", "--group-by", "series", "--bins",
                                                  std::to_string(bins), "--title", labels.title, "--xlabel", labels.x,
                                                  "--ylabel", labels.y, "--out", figure});
}

}  // namespace vaegail::cli
