// registry/cli.h — argument parsing for the shadowlab command (strict: every malformed value is
// an InputError with one clear line).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "core/technique/technique.h"

namespace CLI {
class App;
}

namespace sl::cli {

struct Args {
  std::string command;
  std::map<std::string, std::vector<std::string>> options;  // --key value (repeatable)
  std::vector<std::string> flags;                           // --key without value
  bool has(const std::string& key) const;
  std::optional<std::string> value(const std::string& key) const;
  std::string required(const std::string& key) const;
};

// `shadowlab COMMAND --help`: parse() throws this with the command's help text, which the
// caller prints on stdout with exit status 0.
struct HelpRequested {
  std::string text;
};

// Parses `shadowlab COMMAND [options]` with CLI11: the options that take a value and the flags
// that do not, per command, each with its help line (registry/cli.cpp commandSpecs). An unknown
// command or option, a missing value or a stray argument is an InputError of one line.
Args parse(int argc, char** argv);

// The developer tools' command line (legacy_bench, volumes_bench, shadowlab-twins, csm_bench):
// parses argv into `app`'s options. `--help`/`-h` prints the app's help (one line per option) on
// stdout and returns false, and the caller exits with status 0; a CLI11 parse error (unknown
// option, missing value, stray argument, ...) is an InputError of one line naming `--help`.
// Validation that throws InputError inside the options' callbacks passes through unchanged.
[[nodiscard]] bool parseTool(CLI::App& app, int argc, char** argv);

// Numbers on the command line are strict decimals (core/base/decimal.h): no hexadecimal, inf, nan,
// spaces or trailing characters. Each throws InputError naming the option `what`.
int parsePositiveInt(const std::string& what, const std::string& text, int maxValue);
double parseNumber(const std::string& what, const std::string& text);
void parseSize(const std::string& text, int& width, int& height);  // "800x600"
ImagingChoice parseImaging(const std::string& text);               // "native" or "emulated"
// Fills RenderParams from --size, --shadow-map, --filter, --precision, --param, --backend,
// --imaging.
RenderParams renderParams(const Args& args);
// --camera-distance, --light-radius and --light-position (core/scene/scene.h adjustScene).
SceneAdjustments sceneAdjustments(const Args& args);
glm::vec3 parsePosition(const std::string& what, const std::string& text);  // "X,Y,Z"
// The options among --shadow-map, --filter, --precision and --imaging given explicitly
// (registry/registry.h rejectIgnoredOptions refuses those the technique does not read).
std::vector<CommonOption> givenCommonOptions(const Args& args);

// --orbit AZ,EL,DIST (render, compare, plan and the lab's API; the light is moved by
// --light-position, sceneAdjustments): the camera on a sphere around its target (azimuth about the
// camera's up axis, 0 towards world +z; elevation above the plane normal to that axis; distance in
// world units).
struct ViewPose {
  double azimuthDegrees = 0.0;
  double elevationDegrees = 0.0;
  double distance = 1.0;
  glm::vec3 light{0.0f};
};
ViewPose viewPose(const Scene& scene);  // the scene's own camera and light, in those terms
// Applies --orbit to `scene` and validates it; InputError for a malformed or
// impossible value (a light on its target, an orbit that puts the camera on it).
void applyView(const Args& args, Scene& scene);
// The scene as every command sees it: sceneAdjustments, then applyView (the one place that
// order lives; render, compare, plan and the lab's API all call this).
void viewScene(const Args& args, Scene& scene);

}  // namespace sl::cli
