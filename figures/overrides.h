// figures/overrides.h — `shadowlab figures --only ID --set key=value ...`: one
// figure re-made with parameters changed in every panel, written into its own folder with the
// overrides in the caption and the file names.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/scene.h"
#include "core/technique/technique.h"
#include "figures/figure_spec.h"
#include "registry/cli.h"

namespace sl::figures {

struct FigureOverrides {
  std::vector<std::pair<std::string, std::string>> given;  // key, value, in command-line order
  std::optional<int> width, height;                        // size=WxH
  std::optional<int> shadowMapTexels;                      // shadow-map=N
  std::optional<int> filter;                               // filter=K
  std::optional<Precision> precision;                      // precision=8|12|float
  SceneAdjustments scene;  // camera-distance=X, light-radius=R, light-position=X,Y,Z
  std::map<std::string, std::string> params;  // any other key: a technique's --param key
  bool empty() const { return given.empty(); }
  // "shadow-map=1024, filter=4": as typed, for captions.
  std::string describe() const;
  // "shadow-map-1024--filter-4": for the folder and the file names.
  std::string slug() const;
};

// The keys --set knows besides the techniques' --param keys.
const std::vector<std::string>& overrideKeys();

// Parses the --set values (KEY=VALUE each). A malformed pair, an unknown key spelling, a bad
// value or a key given twice is an InputError of one line.
FigureOverrides parseOverrideList(const std::vector<std::string>& sets);
// --set from the command line; --set without --only is an InputError (one figure at a time).
FigureOverrides parseOverrides(const cli::Args& args);

// The figure with the overrides applied to every panel they concern: its id becomes
// "ID--<slug>" (the folder), `sourceId` keeps the listed id, `overrides` the --set values, the
// caption says what was changed and from what. A key no panel of the figure reads (a --param
// none of its techniques has, --filter on a figure of unfiltered techniques, a scene knob on a
// computed chart) is an InputError naming the keys the figure does read.
FigureSpec applyOverrides(const FigureSpec& figure, const FigureOverrides& overrides);

}  // namespace sl::figures
