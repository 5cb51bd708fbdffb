// lab/web_files.h — the page of the live lab (lab/web/*), embedded at build time
// (lab/embed_web.cmake): the only files the server ever sends.
#pragma once

#include <map>
#include <string>

namespace sl::lab {

struct WebFile {
  std::string contentType;
  std::string text;
};

// "/index.html" -> its type and text.
const std::map<std::string, WebFile>& webFiles();

}  // namespace sl::lab
