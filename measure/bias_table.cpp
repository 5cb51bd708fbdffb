// measure/bias_table.cpp — the depth-bias methods on the stability cases (measure/bias_table.h).
#include "measure/bias_table.h"

#include <cstdio>
#include <iostream>
#include <sstream>
#include <tuple>
#include <utility>

#include "core/technique/technique.h"
#include "measure/stability.h"
#include "registry/registry.h"
#include "registry/shadow_error.h"

namespace sl::measure::bias {

namespace stability = sl::figures::stability;

std::vector<std::string> biasCases() { return {"grazing80", "grazing89", "contact"}; }

std::vector<Variant> biasVariants() {
  return {{"modern.gems16", ""},
          {"modern.gems16", "bicubic"},
          {"modern.gems4", ""},
          {"modern.pcf", ""},
          {"modern.fast-pcf", ""}};
}

std::vector<std::string> biasMethods(const Variant& v) {
  const ParamSpec* bias = findParam(findTechnique(v.technique), "bias");
  if (bias == nullptr) throw std::logic_error("bias table: " + v.technique + " has no bias");
  return bias->choices;
}

std::vector<double> offsetFactors(const Variant& v) {
  const ParamSpec* factor = findParam(findTechnique(v.technique), "offset-factor");
  if (factor == nullptr) return {kNoOffsetFactor};
  constexpr double kNoSlopeOffset = 0.0;
  return {factor->fallback, kNoSlopeOffset};
}

// Over the scored pixels of the reference (receivers facing the light), band included: the share
// of the reference's lit pixels that `visibility` shadows and of its shadowed pixels that it
// lights (each by more than half).
std::pair<double, double> wrongWithBand(const Image& visibility, const Frame& reference) {
  const ShadowTruth truth =
      truthFromReferenceFrame(reference, ErrorMetric::kPoint, false, "the case's reference");
  constexpr float kHalf = 0.5f;
  long long lit = 0, shadowed = 0, litShadowed = 0, shadowedLit = 0;
  for (size_t i = 0; i < visibility.data.size(); ++i) {
    if (truth.scored.data[i] <= kHalf) continue;
    const bool referenceLit = reference.visibility.data[i] > kHalf;
    const bool techniqueLit = visibility.data[i] > kHalf;
    (referenceLit ? lit : shadowed) += 1;
    litShadowed += referenceLit && !techniqueLit;
    shadowedLit += !referenceLit && techniqueLit;
  }
  return {lit > 0 ? double(litShadowed) / double(lit) : 0.0,
          shadowed > 0 ? double(shadowedLit) / double(shadowed) : 0.0};
}

Row measure(const std::string& caseName, const Variant& v, double offsetFactor,
            const std::string& method) {
  stability::Case c = stability::findCase(caseName);
  const auto caseParams = c.params;
  c.params = [&](RenderParams& p) {
    caseParams(p);
    p.extra["bias"] = method;
    if (offsetFactor != kNoOffsetFactor) p.extra["offset-factor"] = std::to_string(offsetFactor);
    if (!v.kernel.empty()) p.extra["kernel"] = v.kernel;
  };
  const stability::Outcome o = stability::evaluate(c, findTechnique(v.technique));
  if (o.kind != stability::Outcome::Kind::kMeasured)
    throw std::logic_error("bias table: " + caseName + " " + v.technique +
                           " not measured: " + o.note);
  Row r;
  r.caseName = caseName;
  r.variant = v;
  r.offsetFactor = offsetFactor;
  r.method = method;
  r.acne = o.selfShadowed();
  const double referenceShadowed = 1.0 - o.referenceLit;
  r.peterPanning = referenceShadowed > 0.0 ? o.wronglyLit.shareAboveHalf / referenceShadowed : 0.0;
  std::tie(r.acneWithBand, r.peterPanningWithBand) =
      wrongWithBand(o.frame.visibility, *o.reference);
  r.finite = o.finite;
  return r;
}

std::vector<Row> measureAll(bool progress) {
  std::vector<Row> rows;
  for (const std::string& c : biasCases())
    for (const Variant& v : biasVariants())
      for (const double factor : offsetFactors(v))
        for (const std::string& m : biasMethods(v)) {
          if (progress)
            std::cerr << "[bias] " << c << " " << v.technique << " " << v.kernel << " " << factor
                      << " " << m << std::endl;
          rows.push_back(measure(c, v, factor, m));
        }
  return rows;
}

std::string percent(double share) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", 100.0 * share);
  return text;
}

std::string markdown(const std::vector<Row>& rows) {
  std::ostringstream md;
  md << "| case | technique | offset-factor | bias | acne (%) | peter-panning (%) | acne, band "
        "included (%) | peter-panning, band included (%) |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    char factor[16] = "none";
    if (r.offsetFactor != kNoOffsetFactor)
      std::snprintf(factor, sizeof factor, "%g", r.offsetFactor);
    md << "| " << r.caseName << " | `" << r.variant.technique
       << (r.variant.kernel.empty() ? "" : " kernel=" + r.variant.kernel) << "` | " << factor
       << " | " << r.method << " | " << percent(r.acne) << " | " << percent(r.peterPanning) << " | "
       << percent(r.acneWithBand) << " | " << percent(r.peterPanningWithBand)
       << (r.finite ? "" : " NaN") << " |\n";
  }
  return md.str();
}

}  // namespace sl::measure::bias
