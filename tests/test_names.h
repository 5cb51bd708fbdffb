// tests/test_names.h — a GoogleTest parameter name from any text: every character that is not
// a letter or digit becomes '_' (GoogleTest accepts only [A-Za-z0-9_] in test names).
#pragma once

#include <cctype>
#include <string>

namespace sl {

inline std::string testName(std::string text) {
  for (char& c : text)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return text;
}

}  // namespace sl
