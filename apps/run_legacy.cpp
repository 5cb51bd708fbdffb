// apps/run_legacy.cpp — `shadowlab run-legacy`: an unchanged OpenGL 1.x GLUT program with the
// drop-in imaging library, every displayed frame written as DIR/NNN.png
// (docs/legacy-programs.md).
//
//   glx        Xvfb (started here when DISPLAY is unset) + Debian's freeglut + GLX on
//              llvmpipe, with LD_PRELOAD=libshadowlab-imaging.so:libshadowlab-frames.so — the
//              path a user has.
//   osmesa     the project's headless GLUT (libshadowlab-glut.so) on Debian's OSMesa, with
//              libshadowlab-imaging.so: no window system at all.
//   reference  the headless GLUT on the reference Mesa 7.8.2 (native imaging; the imaging
//              library is preloaded too and passes it through).
//
// The program's stdout and stderr pass through; its exit status is the command's. The frames
// appear only when the program ended with status 0 and showed every frame asked for.
#include "apps/run_legacy.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/base/errors.h"
#include "core/base/provenance.h"
#include "core/gl/context.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

constexpr double kDefaultTimeoutSeconds = 60.0;  // a Red Book program shows a frame in < 1 s
constexpr int kXvfbStartSeconds = 15;            // Xvfb names its display within this
constexpr auto kPollInterval = std::chrono::milliseconds(20);
constexpr const char* kXvfbScreen = "1280x1024x24";      // larger than the Red Book windows
constexpr int kExitSignalBase = 128;                     // shell convention for a killed program
constexpr const char* kDebianOsmesa = "libOSMesa.so.8";  // Debian 12's OSMesa (libosmesa6)

const char* kRunLegacyHelp =
    R"(usage: shadowlab run-legacy --backend glx|osmesa|reference [--keys "h v l"] --frames DIR [--timeout S]
                           -- PROGRAM [ARGS...]
Runs an unchanged OpenGL 1.x GLUT program with the imaging subset preloaded
(build/lib/libshadowlab-imaging.so) and writes each displayed frame as DIR/NNN.png: 000.png
after start-up, then one after each key of --keys (one character each, or esc / space),
delivered to the program's keyboard callback. After the last frame the main loop is left as
when the window is closed. The program runs in the current directory; its stdout and stderr
pass through and its exit status is the command's.
  --backend glx        Xvfb (started when DISPLAY is unset) + freeglut + GLX on llvmpipe
  --backend osmesa     the project's headless GLUT on Debian's OSMesa (no display needed)
  --backend reference  the headless GLUT on the reference Mesa 7.8.2 (native imaging;
                       $SHADOWLAB_REFERENCE_GL or ../shared/reference-gl)
  --frames DIR    must not exist or be empty; filled only when the run succeeds
  --timeout S     seconds before the program is stopped (exit 3); default 60
)";

struct Options {
  std::string backend;
  std::string keys;
  std::string frames;
  double timeout = kDefaultTimeoutSeconds;
  std::vector<std::string> program;
};

// The directory of the running shadowlab binary (build/bin): the libraries are in ../lib.
fs::path binaryDirectory() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw GlError("cannot find the shadowlab binary's folder: " + ec.message());
  return exe.parent_path();
}

fs::path libraryPath(const char* name) {
  const fs::path p = (binaryDirectory() / ".." / "lib" / name).lexically_normal();
  if (!fs::exists(p))
    throw GlError(p.string() + " is missing (build it: cmake --build build --target " +
                  std::string(name).substr(3, std::strlen(name) - 6) + ")");
  return p;
}

// PROGRAM as execv runs it: a path with a slash as given, else the first match on PATH.
std::string findProgram(const std::string& name) {
  auto runnable = [](const fs::path& p) {
    return fs::is_regular_file(p) && access(p.c_str(), X_OK) == 0;
  };
  if (name.find('/') != std::string::npos) {
    if (!runnable(name)) throw InputError("program '" + name + "' is not an executable file");
    return name;
  }
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path != nullptr ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':'))
    if (!dir.empty() && runnable(fs::path(dir) / name)) return (fs::path(dir) / name).string();
  throw InputError("program '" + name + "' is not found on PATH");
}

Options parseOptions(int argc, char** argv) {
  // Everything after "--" is the program and its arguments, untouched.
  int split = argc;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--") == 0) {
      split = i;
      break;
    }
  Options o;
  CLI::App app("shadowlab run-legacy", "run-legacy");
  app.set_help_flag();
  bool help = false;
  app.add_flag("--help,-h", help);
  app.add_option("--backend", o.backend);
  app.add_option("--keys", o.keys);
  app.add_option("--frames", o.frames);
  app.add_option("--timeout", o.timeout);
  std::vector<std::string> before;
  for (int i = split - 1; i >= 1; --i) before.emplace_back(argv[i]);  // CLI11 wants reversed
  try {
    app.parse(before);
  } catch (const CLI::ParseError& e) {
    throw InputError(std::string("run-legacy: ") + e.what());
  }
  if (help) {
    std::cout << kRunLegacyHelp;
    std::exit(0);
  }
  for (int i = split + 1; i < argc; ++i) o.program.emplace_back(argv[i]);
  if (o.backend.empty())
    throw InputError("run-legacy: --backend is required (glx, osmesa or reference)");
  if (o.backend != "glx" && o.backend != "osmesa" && o.backend != "reference")
    throw InputError("run-legacy: unknown --backend '" + o.backend +
                     "' (expected glx, osmesa or reference)");
  if (o.frames.empty()) throw InputError("run-legacy: --frames DIR is required");
  if (o.program.empty()) throw InputError("run-legacy: no program after '--'");
  if (!(o.timeout > 0)) throw InputError("run-legacy: --timeout must be a positive number");
  std::istringstream words(o.keys);
  std::string w;
  while (words >> w)
    if (w.size() != 1 && w != "esc" && w != "space")
      throw InputError("run-legacy: key '" + w + "' is not one character, esc or space");
  return o;
}

// A child process that we started and end (SIGTERM) when we leave.
struct Child {
  pid_t pid = -1;
  Child() = default;
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    if (pid > 0) {
      kill(pid, SIGTERM);
      waitpid(pid, nullptr, 0);
    }
  }
};

// Starts Xvfb on a display number it chooses (-displayfd) and returns ":N".
std::string startXvfb(Child& xvfb) {
  int fds[2];
  if (pipe(fds) != 0) throw GlError("cannot create a pipe for Xvfb");
  xvfb.pid = fork();
  if (xvfb.pid < 0) throw GlError("cannot fork for Xvfb");
  if (xvfb.pid == 0) {
    close(fds[0]);
    const int devnull = open("/dev/null", O_WRONLY);
    if (devnull >= 0) {
      dup2(devnull, STDOUT_FILENO);
      dup2(devnull, STDERR_FILENO);
    }
    const std::string fd = std::to_string(fds[1]);
    execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", kXvfbScreen, "-nolisten",
           "tcp", "-noreset", static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  std::string number;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kXvfbStartSeconds);
  while (std::chrono::steady_clock::now() < deadline) {
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, int(kPollInterval.count())) <= 0) continue;
    char c = 0;
    if (read(fds[0], &c, 1) != 1) break;
    if (c == '\n') break;
    number += c;
  }
  close(fds[0]);
  if (number.empty())
    throw GlError(
        "Xvfb did not start (install it: scripts/setup.sh installs xvfb), or set DISPLAY");
  return ":" + number;
}

// DIR must be new or an empty directory; frames go to a sibling first.
void checkFramesDir(const fs::path& dir) {
  if (!fs::exists(dir)) return;
  if (!fs::is_directory(dir)) throw InputError("--frames " + dir.string() + " is not a directory");
  if (!fs::is_empty(dir)) throw InputError("--frames " + dir.string() + " is not empty");
}

// What is preloaded, in lookup order, for each back end.
std::string preloadFor(const Options& o) {
  if (o.backend == "glx")
    return libraryPath("libshadowlab-imaging.so").string() + ":" +
           libraryPath("libshadowlab-frames.so").string();
  const std::string glut = libraryPath("libshadowlab-glut.so").string();
  if (o.backend == "osmesa")
    return libraryPath("libshadowlab-imaging.so").string() + ":" + glut + ":" + kDebianOsmesa;
  const std::string reference = referenceGlPath();
  if (reference.empty() || !fs::exists(reference))
    throw GlError(
        "the reference GL (Mesa 7.8.2) is not here: set SHADOWLAB_REFERENCE_GL or "
        "place it at ../shared/reference-gl");
  // The imaging library stays out of the way of the native subset (it only traces, when
  // SHADOWLAB_IMAGING_TRACE asks), as it does on any GL that has GL_ARB_imaging.
  return libraryPath("libshadowlab-imaging.so").string() + ":" + glut + ":" + reference;
}

int runProgramWithFrames(const Options& o) {
  std::string preload = preloadFor(o);
  const std::string program = findProgram(o.program[0]);
  const fs::path dir = fs::absolute(o.frames);
  checkFramesDir(dir);
  fs::create_directories(dir.parent_path());
  const fs::path partial = dir.string() + ".partial-" + std::to_string(getpid());
  fs::remove_all(partial);
  fs::create_directories(partial);

  Child xvfb;
  std::string display;
  if (const char* d = std::getenv("DISPLAY"); d != nullptr && *d != 0)
    display = d;
  else if (o.backend == "glx")
    display = startXvfb(xvfb);

  if (const char* p = std::getenv("LD_PRELOAD"); p != nullptr && *p != 0)
    preload += ":" + std::string(p);
  Child child;
  child.pid = fork();
  if (child.pid < 0) throw GlError("cannot fork for the program");
  if (child.pid == 0) {
    if (!display.empty()) setenv("DISPLAY", display.c_str(), 1);
    setenv("LD_PRELOAD", preload.c_str(), 1);
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);  // llvmpipe, whatever GPU the machine has
    setenv("SHADOWLAB_FRAMES_DIR", partial.c_str(), 1);
    setenv("SHADOWLAB_KEYS", o.keys.c_str(), 1);
    setenv("SHADOWLAB_FRAMES_COMMAND", commandLine().c_str(), 1);
    std::vector<char*> args;
    for (const std::string& a : o.program) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(program.c_str(), args.data());
    std::fprintf(stderr, "shadowlab run-legacy: cannot run %s: %s\n", program.c_str(),
                 std::strerror(errno));
    _exit(kExitGlError);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(o.timeout);
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(child.pid, &status, WNOHANG);
    if (done == child.pid) break;
    if (std::chrono::steady_clock::now() > deadline) {
      kill(child.pid, SIGKILL);
      waitpid(child.pid, &status, 0);
      child.pid = -1;
      fs::remove_all(partial);
      throw GlError("the program did not finish within " + formatNumber(o.timeout) +
                    " s (a key that shows no frame?)");
    }
    std::this_thread::sleep_for(kPollInterval);
  }
  child.pid = -1;
  const int code = WIFEXITED(status)
                       ? WEXITSTATUS(status)
                       : kExitSignalBase + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  if (code != 0) {
    fs::remove_all(partial);
    return code;
  }
  size_t wanted = 1;
  std::istringstream words(o.keys);
  for (std::string w; words >> w;) ++wanted;
  size_t written = 0;
  for (const auto& e : fs::directory_iterator(partial)) written += e.path().extension() == ".png";
  if (written != wanted) {
    fs::remove_all(partial);
    throw GlError("the program showed " + std::to_string(written) + " of the " +
                  std::to_string(wanted) + " frames asked for (1 after start-up, 1 per key)");
  }
  if (fs::exists(dir)) fs::remove(dir);  // empty (checked above)
  fs::rename(partial, dir);
  return 0;
}

}  // namespace

int runLegacy(int argc, char** argv) {
  const Options o = parseOptions(argc, argv);
  return runProgramWithFrames(o);
}

}  // namespace sl
