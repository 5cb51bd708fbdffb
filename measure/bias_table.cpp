// measure/bias_table.cpp — the depth-bias methods on the stability cases (measure/bias_table.h).
#include "measure/bias_table.h"

#include <cstdio>
#include <iostream>
#include <sstream>

#include "core/technique/technique.h"
#include "measure/stability.h"
#include "registry/registry.h"

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
  md << "| case | technique | offset-factor | bias | acne (%) | peter-panning (%) |\n"
     << "|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    char factor[16] = "none";
    if (r.offsetFactor != kNoOffsetFactor)
      std::snprintf(factor, sizeof factor, "%g", r.offsetFactor);
    md << "| " << r.caseName << " | `" << r.variant.technique
       << (r.variant.kernel.empty() ? "" : " kernel=" + r.variant.kernel) << "` | " << factor
       << " | " << r.method << " | " << percent(r.acne) << " | " << percent(r.peterPanning)
       << (r.finite ? "" : " NaN") << " |\n";
  }
  return md.str();
}

}  // namespace sl::measure::bias
