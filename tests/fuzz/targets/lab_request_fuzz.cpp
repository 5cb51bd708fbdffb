// tests/fuzz/targets/lab_request_fuzz.cpp — libFuzzer target of the lab's request parser
// (lab/lab_request.h parseRequest): the bytes are the query of a GET /api/render request (what
// follows '?', URL-encoded as a browser sends it), parsed with the views that path serves
// (lab/lab_server.cpp). Corpus: tests/fuzz/corpus/lab_request/. Run: scripts/fuzz.sh;
// replayed by tests/fuzz.
#include <httplib.h>

#include "fuzz/targets/fuzz_target.h"
#include "lab/lab_request.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return sl::fuzz::acceptLoadedOrInputError([&] {
    httplib::Request req;
    req.method = "GET";
    req.path = "/api/render";
    req.target = "/api/render?" + sl::fuzz::bytesAsString(data, size);
    sl::lab::parseRequest(req, {"image", "mask", "passes"});
  });
}
