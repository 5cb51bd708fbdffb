// core/base/html.h — text into HTML: the pass dumps' index.html and the report share one escape.
#pragma once

#include <string>

namespace sl {

// `text` with &, <, > and " replaced by their character references (safe in element content
// and in double-quoted attribute values).
std::string htmlEscape(const std::string& text);

// `text` escaped as htmlEscape does, with each `...` (a command, key or option) as
// <code>...</code>; an unpaired ` opens a <code> closed at the end.
std::string htmlWithCode(const std::string& text);

}  // namespace sl
