// measure/bias_table.h — the depth-bias methods of the PCF family (--param bias: constant,
// receiver-plane, normal-offset; modern/pcf_bias.h) on the stability suite's
// acne-prone cases: how much of the lit receiver each one shadows (acne) and how much of the
// shadow it lights (peter-panning), against the ray-traced reference. tools/bias_table.cpp
// prints the table (docs/bias.md is its output); tests/stability asserts on the rows.
#pragma once

#include <string>
#include <vector>

namespace sl::measure::bias {

// The cases measured (measure/stability.cpp): the grazing light at 80 and 89 degrees (the
// ground casts and receives: acne-prone) and the casters resting on the ground (contact).
std::vector<std::string> biasCases();
// The techniques (with their --params) and methods measured.
struct Variant {
  std::string technique;
  std::string kernel;  // "" (the technique's own) or "bicubic" (modern.gems16 only)
};
std::vector<Variant> biasVariants();
// The methods a variant's technique declares (its --param bias choices).
std::vector<std::string> biasMethods(const Variant& v);
// The light pass's polygon-offset slope factors measured where the technique has one (GPU Gems
// PCF): its default (4) and 0, where the method alone must handle the receiver's slope. The
// Brabec–Seidel twins have none: kNoOffsetFactor.
constexpr double kNoOffsetFactor = -1.0;
std::vector<double> offsetFactors(const Variant& v);

struct Row {
  std::string caseName;
  Variant variant;
  double offsetFactor = kNoOffsetFactor;
  std::string method;
  // Of the stability suite's counted pixels (outside the reference's 2-pixel edge band, on
  // receivers facing the light): the share of those the reference shows lit that the technique
  // shadows, and of those the reference shows shadowed that the technique lights.
  double acne = 0;
  double peterPanning = 0;
  // The same over every scored pixel, the edge band included: a shadow moved by a texel or
  // two from its caster shows here first (at 160x120 a texel of the 512 map is about a pixel).
  double acneWithBand = 0;
  double peterPanningWithBand = 0;
  bool finite = true;
};

// One row: the case rendered at the stability suite's size (160x120, map 512).
Row measure(const std::string& caseName, const Variant& v, double offsetFactor,
            const std::string& method);
// Every case x variant x offset factor x method.
std::vector<Row> measureAll(bool progress);
// The rows as a markdown table (percentages to 0.01%).
std::string markdown(const std::vector<Row>& rows);

}  // namespace sl::measure::bias
