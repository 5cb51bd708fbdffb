// core/technique/pass_run_key.h — which run of which pass a PassTime is, so that the same pass is
// found again in the next frame of the same render: by its pass-table id and part (typed fields
// of core/technique/pass_table.h), never by its display name. A hand-timed pass (PassTimer, no
// table: the floors of measure/) has no id, and its name is all it has.
#pragma once

#include <string>
#include <tuple>

#include "core/technique/technique.h"

namespace sl {

struct PassRunKey {
  std::string id;       // PassSpec::id ("3", "5b", "mesh"); empty for a hand-timed pass
  int part = 0;         // PassPart::index: which of the pass's repeated runs
  std::string timedAs;  // a hand-timed pass's name; empty for a pass of a table
  auto operator<=>(const PassRunKey&) const = default;
};

inline PassRunKey passRunKey(const PassTime& pass) {
  if (pass.id.empty()) return {"", 0, pass.name};
  return {pass.id, pass.part, ""};
}

}  // namespace sl
