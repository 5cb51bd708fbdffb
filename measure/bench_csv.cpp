// measure/bench_csv.cpp — the bench rows as CSV (--csv; the Python module reads the same text):
// the JSON line's fields as columns (measure/bench.h writeCsvRows).
#include <iterator>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <string>

#include "core/base/errors.h"
#include "core/base/output_files.h"
#include "core/base/provenance.h"
#include "measure/bench.h"

namespace sl::figures {
namespace {
// The columns of one reference's errors (registry/shadow_error.h), each prefixed with the
// reference: hard_rmse, soft_point_leak_share, ...
constexpr const char* kErrorColumns[] = {"rmse",      "max_abs",      "share_above_half",
                                         "band_rmse", "band_max_abs", "band_share_above_half",
                                         "leak_share"};
constexpr size_t kErrorColumnsPerReference = std::size(kErrorColumns);
}  // namespace

void writeCsvRows(std::ostream& out, const std::vector<BenchRow>& rows) {
  // The JSON line's fields as columns: the common options empty where the technique does not
  // read them, "params" the same JSON object as the line's (CSV-quoted, quotes doubled).
  out << "scene,technique,variant,status,reference,width,height,orbit,shadow_map,filter,"
         "precision,params,frame_ms,frames_timed,frame_iqr_ms,frame_min_ms,spread_large,wall_ms,"
         "pareto_rank";
  // hard_*, soft_*: against the pixel-integrated references (pixel=area, the primary truth);
  // hard_point_*, soft_point_*: against the pixel-centre references.
  for (const char* ref : {"hard", "soft", "hard_point", "soft_point"})
    for (const char* m : kErrorColumns) out << "," << ref << "_" << m;
  // The one error definition's scored pixels (docs/error.md): how many, and the share left out.
  out << ",metric,scored_pixels,left_out_share,temporal_change,reference_temporal_change,passes,"
         "load_before,load_after,backend,gl_vendor,gl_renderer,gl_version,date,commit,command\n";
  auto csvField = [](const std::string& s) {  // RFC 4180: in quotes, inner quotes doubled
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
  };
  auto quoted = [](std::string s) {
    for (char& c : s)
      if (c == '"') c = '\'';
    return "\"" + s + "\"";
  };
  for (const BenchRow& r : rows) {
    const nlohmann::json params = effectiveParamsJson(r);
    auto common = [&](const char* key) -> std::string {  // empty: not read by the technique
      if (!params.contains(key)) return "";
      return params.at(key).is_string() ? params.at(key).get<std::string>() : params.at(key).dump();
    };
    const bool ran = r.status == "ok";
    auto timing = [&](double v) { return ran ? formatNumber(v) : std::string(); };
    // At the stream's precision (the Python module reads full doubles); empty: did not run.
    auto measured = [&](double v) {
      std::ostringstream s;
      s.precision(out.precision());
      if (ran) s << v;
      return s.str();
    };
    out << r.scene << "," << r.technique << "," << quoted(r.variant) << "," << quoted(r.status)
        << "," << r.primaryReference << "," << r.params.width << "," << r.params.height << ","
        << quoted(r.orbit) << "," << common("shadow_map") << "," << common("filter") << ","
        << common("precision") << ","
        << csvField(params.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace)) << ","
        << measured(r.frameMs) << "," << (ran ? std::to_string(r.framesTimed) : "") << ","
        << timing(r.iqrMs()) << "," << timing(r.minFrameMs) << ","
        << (ran ? (r.spreadLarge() ? "1" : "0") : "") << "," << measured(r.wallMs) << ",";
    if (r.paretoRank > 0) out << r.paretoRank;  // empty: a reference, or a row that did not run
    // Empty where not measured, as the JSON line leaves them out: every error of a row that did
    // not run, and the soft references' columns of a scene without reference.soft.
    for (const ErrorSet* e : {&r.hard, &r.soft, &r.hardPoint, &r.softPoint}) {
      const bool softColumn = e == &r.soft || e == &r.softPoint;
      if (!ran || (softColumn && !r.softMeasured)) {
        out << std::string(kErrorColumnsPerReference, ',');
        continue;
      }
      out << "," << e->all.rmse << "," << e->all.maxAbs << "," << e->all.shareAboveHalf << ","
          << e->band.rmse << "," << e->band.maxAbs << "," << e->band.shareAboveHalf << ","
          << e->leakShare;
    }
    if (ran)
      out << "," << r.primary().metric << "," << r.primary().counts.scored << ","
          << r.primary().counts.leftOutShare();
    else
      out << ",,,";
    // Empty where not measured.
    for (double v : {r.temporalChange, r.referenceTemporalChange}) {
      out << ",";
      if (v >= 0) out << v;
    }
    std::string passes;
    for (const PassTime& p : r.passes)
      passes += (passes.empty() ? "" : "; ") + p.name + "=" + std::to_string(p.milliseconds);
    out << "," << quoted(passes);
    for (double load : {r.loadBefore, r.loadAfter}) {
      out << ",";
      if (load >= 0) out << load;
    }
    out << "," << quoted(r.backend) << "," << quoted(r.glVendor) << "," << quoted(r.glRenderer)
        << "," << quoted(r.glVersion) << "," << r.date << "," << quoted(buildCommit()) << ","
        << csvField(commandLine()) << "\n";
  }
}

void writeCsv(const std::string& path, const std::vector<BenchRow>& rows) {
  writeFileAtomically(path, [&](std::ostream& out) { writeCsvRows(out, rows); });
}

}  // namespace sl::figures
