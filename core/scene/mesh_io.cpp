#include "core/scene/mesh_io.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <zlib.h>

#include <algorithm>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <system_error>
#include <vector>

#include "core/base/errors.h"
#include "core/scene/primitives.h"

// Why the checks below exist: Assimp 5.2's PLY reader walks its 1 MiB line cache
// (IOStreamBuffer::getNextLine) with an end-of-data test of `pos == size` and skips a line
// end with `while (cache[pos] != '\n') ++pos`, although '\0' and '\r' also count as line
// ends; its header parser (PLY::DOM::ParseHeader) keeps asking for lines until it meets
// `end_header` without looking at whether one came. A header with no `end_header` line, or one
// whose lines end in '\0' or '\r' (binary data, a file with no newline), makes it loop for ever
// or step past the end of the cache and read until the process faults: the segfault depends on
// what lies after the cache on the heap. Counts the header declares are allocated as declared.
// So a PLY reaches Assimp only with a complete, well-formed header whose counts are bounded by
// the bytes that follow it, and every buffer ends in '\n'.

namespace sl {
namespace {
namespace fs = std::filesystem;

// zlib inflates into chunks of this many bytes; the decompressed total is checked per chunk.
constexpr std::size_t kInflateChunkBytes = std::size_t(1) << 16;
// A PLY header is a few hundred bytes (the dragon's is 196); longer is not a mesh header.
constexpr std::size_t kMaxPlyHeaderBytes = std::size_t(64) << 10;
// zlib's windowBits for a gzip wrapper: the largest window (15) plus 16 for the gzip header.
constexpr int kGzipWindowBits = 15 + 16;

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// A float as printf's %g writes it ("1e+18"), for messages.
std::string shortNumber(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(value));
  return text;
}

std::string lowerCase(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

enum class MeshFormat { kObj, kPly };

struct MeshFileKind {
  MeshFormat format;
  bool gzipped;
};

MeshFileKind classifyMeshFile(const std::string& path) {
  const std::string name = lowerCase(fs::path(path).filename().string());
  const bool gzipped = endsWith(name, ".gz");
  const std::string inner = gzipped ? name.substr(0, name.size() - 3) : name;
  if (endsWith(inner, ".obj")) return {MeshFormat::kObj, gzipped};
  if (endsWith(inner, ".ply")) return {MeshFormat::kPly, gzipped};
  throw InputError("mesh file " + path + " is not .obj or .ply (optionally .gz)");
}

// The whole file, refused before reading when it is larger than kMaxMeshFileBytes.
std::string readMeshFileBytes(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError("cannot open mesh file " + path);
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec) throw InputError("cannot read mesh file " + path + ": " + ec.message());
  if (bytes > kMaxMeshFileBytes)
    throw InputError("mesh file " + path + " has " + std::to_string(bytes) + " bytes; at most " +
                     std::to_string(kMaxMeshFileBytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open mesh file " + path);
  std::string data(std::size_t(bytes), '\0');
  in.read(data.data(), std::streamsize(bytes));
  if (std::uintmax_t(in.gcount()) != bytes) throw InputError("cannot read mesh file " + path);
  return data;
}

// Inflates one or more concatenated gzip members, refusing the data as soon as the output
// passes kMaxDecompressedMeshBytes, and refusing truncated, corrupt or trailing data.
std::string gunzipMeshBytes(const std::string& compressed, const std::string& path) {
  z_stream z{};
  if (inflateInit2(&z, kGzipWindowBits) != Z_OK)
    throw InputError("mesh file " + path + ": cannot start gzip decompression");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  z.avail_in = uInt(compressed.size());  // at most kMaxMeshFileBytes, which fits a uInt
  std::string out;
  std::vector<char> chunk(kInflateChunkBytes);
  std::string problem;
  for (;;) {
    z.next_out = reinterpret_cast<Bytef*>(chunk.data());
    z.avail_out = uInt(chunk.size());
    const int status = inflate(&z, Z_NO_FLUSH);
    const std::size_t produced = chunk.size() - z.avail_out;
    if (out.size() + produced > kMaxDecompressedMeshBytes) {
      problem = "decompresses to more than " + std::to_string(kMaxDecompressedMeshBytes) +
                " bytes; at most " + std::to_string(kMaxDecompressedMeshBytes) + " are accepted";
      break;
    }
    out.append(chunk.data(), produced);
    if (status == Z_STREAM_END) {
      if (z.avail_in == 0) break;              // the last member ended with the file
      if (inflateReset(&z) == Z_OK) continue;  // another gzip member follows
    }
    if (status == Z_OK) continue;
    if (status == Z_BUF_ERROR && z.avail_in == 0) {
      problem = "truncated gzip data";
    } else {
      problem = std::string("corrupt gzip data") +
                (z.msg != nullptr ? std::string(" (") + z.msg + ")" : "");
    }
    break;
  }
  inflateEnd(&z);
  if (!problem.empty()) throw InputError("mesh file " + path + ": " + problem);
  return out;
}

// ---- PLY sanity check -------------------------------------------------------------------------

enum class PlyEncoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyProperty {
  bool isList = false;
  int countBytes = 0;  // lists: size of the count (an integer type)
  int valueBytes = 0;  // scalars: size of the value; lists: size of each item
  bool countSigned = false;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::kAscii;
  std::vector<PlyElement> elements;
  std::size_t bodyOffset = 0;  // first byte after the `end_header` line
};

// Size in bytes of a PLY scalar type name (both spellings of the specification), or 0.
int plyTypeBytes(const std::string& type, bool* isInteger, bool* isSigned) {
  struct Type {
    const char* a;
    const char* b;
    int bytes;
    bool integer;
    bool isSigned;
  };
  static const Type kTypes[] = {
      {"char", "int8", 1, true, true},      {"uchar", "uint8", 1, true, false},
      {"short", "int16", 2, true, true},    {"ushort", "uint16", 2, true, false},
      {"int", "int32", 4, true, true},      {"uint", "uint32", 4, true, false},
      {"float", "float32", 4, false, true}, {"double", "float64", 8, false, true}};
  for (const Type& t : kTypes)
    if (type == t.a || type == t.b) {
      *isInteger = t.integer;
      *isSigned = t.isSigned;
      return t.bytes;
    }
  return 0;
}

// Spaces and tabs separate the words of a PLY line; a '\r' before the '\n' ends it.
bool isWordSeparator(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// The next word of `line` at or after `*at`, and `*at` moved past it; empty at the end.
std::string_view nextWord(std::string_view line, std::size_t* at) {
  std::size_t i = *at;
  while (i < line.size() && isWordSeparator(line[i])) ++i;
  const std::size_t start = i;
  while (i < line.size() && !isWordSeparator(line[i])) ++i;
  *at = i;
  return line.substr(start, i - start);
}

std::vector<std::string> splitWords(std::string_view line) {
  std::vector<std::string> words;
  std::size_t at = 0;
  for (std::string_view w = nextWord(line, &at); !w.empty(); w = nextWord(line, &at))
    words.emplace_back(w);
  return words;
}

std::size_t countWords(std::string_view line) {
  std::size_t words = 0;
  for (std::size_t i = 0; i < line.size(); ++i)
    if (!isWordSeparator(line[i]) && (i == 0 || isWordSeparator(line[i - 1]))) ++words;
  return words;
}

bool parseCount(std::string_view word, std::uint64_t* value) {
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, *value);
  return ec == std::errc() && ptr == end;
}

// Reads the header line by line: `ply`, one known `format`, comments, `element NAME COUNT`
// with `property TYPE NAME` / `property list COUNTTYPE ITEMTYPE NAME` lines, `end_header`.
PlyHeader parsePlyHeader(const std::string& data, const std::string& path) {
  auto bad = [&](const std::string& why) {
    return InputError("malformed PLY file " + path + ": " + why);
  };
  PlyHeader header;
  std::size_t pos = 0;
  int lineNumber = 0;
  bool sawFormat = false;
  for (;;) {
    const std::size_t newline = data.find('\n', pos);
    if (newline == std::string::npos || newline >= kMaxPlyHeaderBytes)
      throw bad("no end_header line (a header has at most " + std::to_string(kMaxPlyHeaderBytes) +
                " bytes)");
    std::string_view line(data.data() + pos, newline - pos);
    pos = newline + 1;
    ++lineNumber;
    // "\r\n" line ends are fine in ascii files; Assimp's binary reader would take the '\n'
    // after a '\r' for the first data byte, so binary headers must end lines in '\n' alone.
    if (!line.empty() && line.back() == '\r') {
      if (sawFormat && header.encoding != PlyEncoding::kAscii)
        throw bad("binary header lines must end in \\n alone (line " + std::to_string(lineNumber) +
                  ")");
      line.remove_suffix(1);
    }
    for (const char c : line)
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
        throw bad("control character in header line " + std::to_string(lineNumber) +
                  " (header lines end in \\n)");
    const std::vector<std::string> w = splitWords(line);
    if (lineNumber == 1) {
      if (w.size() != 1 || lowerCase(w[0]) != "ply") throw bad("first line is not 'ply'");
      continue;
    }
    if (w.empty()) throw bad("empty header line " + std::to_string(lineNumber));
    if (w[0] == "comment" || w[0] == "obj_info") continue;
    if (lineNumber == 2) {
      if (w.size() != 3 || w[0] != "format") throw bad("second line is not a format line");
      if (w[1] == "ascii") {
        header.encoding = PlyEncoding::kAscii;
      } else if (w[1] == "binary_little_endian") {
        header.encoding = PlyEncoding::kBinaryLittleEndian;
      } else if (w[1] == "binary_big_endian") {
        header.encoding = PlyEncoding::kBinaryBigEndian;
      } else {
        throw bad("unknown format '" + w[1] + "'");
      }
      sawFormat = true;
      continue;
    }
    if (w[0] == "end_header") {
      if (w.size() != 1) throw bad("text after end_header");
      break;
    }
    if (w[0] == "element") {
      PlyElement e;
      if (w.size() != 3 || !parseCount(w[2], &e.count))
        throw bad("header line " + std::to_string(lineNumber) + " is not 'element NAME COUNT'");
      e.name = w[1];
      for (const PlyElement& other : header.elements)
        if (other.name == e.name) throw bad("element '" + e.name + "' declared twice");
      header.elements.push_back(e);
      continue;
    }
    if (w[0] == "property") {
      if (header.elements.empty()) throw bad("property before any element");
      PlyProperty p;
      bool integer = false, isSigned = false;
      if (w.size() == 5 && w[1] == "list") {
        p.isList = true;
        p.countBytes = plyTypeBytes(w[2], &integer, &p.countSigned);
        if (p.countBytes == 0 || !integer)
          throw bad("list count type '" + w[2] + "' is not an integer type");
        p.valueBytes = plyTypeBytes(w[3], &integer, &isSigned);
        if (p.valueBytes == 0) throw bad("unknown property type '" + w[3] + "'");
      } else if (w.size() == 3) {
        p.valueBytes = plyTypeBytes(w[1], &integer, &isSigned);
        if (p.valueBytes == 0) throw bad("unknown property type '" + w[1] + "'");
      } else {
        throw bad("header line " + std::to_string(lineNumber) + " is not a property");
      }
      header.elements.back().properties.push_back(p);
      continue;
    }
    throw bad("unknown header line '" + w[0] + "'");
  }
  if (!sawFormat) throw bad("no format line");
  for (const PlyElement& e : header.elements)
    if (e.properties.empty()) throw bad("element '" + e.name + "' has no properties");
  header.bodyOffset = pos;
  return header;
}

// The declared vertex and face counts against the caps (before anything is allocated).
void checkPlyCounts(const PlyHeader& header, const std::string& path) {
  for (const PlyElement& e : header.elements) {
    if (e.name == "vertex" && e.count > kMaxMeshVertices)
      throw InputError("PLY file " + path + " declares " + std::to_string(e.count) +
                       " vertices; at most " + std::to_string(kMaxMeshVertices));
    if ((e.name == "face" || e.name == "tristrips") && e.count > kMaxMeshTriangles)
      throw InputError("PLY file " + path + " declares " + std::to_string(e.count) + " " + e.name +
                       " entries; at most " + std::to_string(kMaxMeshTriangles));
  }
}

// Tallies the triangles a face (or triangle strip) list of `items` indices makes, refusing the
// file as soon as the total passes kMaxMeshTriangles.
class TriangleTally {
 public:
  TriangleTally(const std::string& path, const char* format) : path_(path), format_(format) {}
  void addPolygon(std::uint64_t corners) {
    if (corners > 2) triangles_ += corners - 2;
    if (triangles_ > kMaxMeshTriangles)
      throw InputError(std::string(format_) + " file " + path_ + " declares more than " +
                       std::to_string(kMaxMeshTriangles) + " triangles; at most " +
                       std::to_string(kMaxMeshTriangles));
  }

 private:
  const std::string& path_;
  const char* format_;
  std::uint64_t triangles_ = 0;
};

bool isFaceElement(const PlyElement& e) { return e.name == "face" || e.name == "tristrips"; }

std::string declaredInstance(const PlyElement& e, std::uint64_t i) {
  return e.name + " " + std::to_string(i) + " of " + std::to_string(e.count);
}

// A word of an ascii PLY body is a decimal number (an optional sign, digits, a point, an
// exponent): Assimp's reader skips over anything else without failing, and a line it misreads
// so can leave it reading past the body (a file found by tests/fuzz leaked in Assimp that way).
bool isNumberWord(std::string_view word) {
  if (!word.empty() && word.front() == '+') word.remove_prefix(1);
  double value = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc() && end == word.data() + word.size();
}

// An ascii body has one line per element instance, each with a word per scalar property and,
// per list property, a count word followed by that many words (Assimp reads them so).
void checkPlyAsciiBody(const std::string& data, const PlyHeader& header, const std::string& path) {
  TriangleTally triangles(path, "PLY");
  std::size_t pos = header.bodyOffset;
  for (const PlyElement& e : header.elements) {
    // Each instance takes a line of at least two bytes: a digit and its line end.
    if (e.count > (data.size() - pos) / 2)
      throw InputError("PLY file " + path + " declares " + std::to_string(e.count) + " " + e.name +
                       " lines but has only " + std::to_string(data.size() - pos) +
                       " bytes left for them");
    for (std::uint64_t i = 0; i < e.count; ++i) {
      const std::size_t newline = data.find('\n', pos);
      if (newline == std::string::npos)
        throw InputError("PLY file " + path + " ends before " + declaredInstance(e, i));
      const std::string_view line(data.data() + pos, newline - pos);
      pos = newline + 1;
      std::size_t at = 0;  // where the next word of the line starts
      for (const PlyProperty& p : e.properties) {
        std::uint64_t items = 1;
        if (p.isList) {
          if (!parseCount(nextWord(line, &at), &items))
            throw InputError("PLY file " + path + ": " + declaredInstance(e, i) +
                             " lacks a list count");
          if (isFaceElement(e)) triangles.addPolygon(items);
        }
        for (std::uint64_t k = 0; k < items; ++k) {
          const std::string_view word = nextWord(line, &at);
          if (word.empty())
            throw InputError("PLY file " + path + ": " + declaredInstance(e, i) +
                             " has too few values");
          if (!isNumberWord(word))
            throw InputError("PLY file " + path + ": " + declaredInstance(e, i) +
                             " has a value that is not a number");
        }
      }
    }
  }
}

std::uint64_t readPlyCount(const char* bytes, const PlyProperty& p, bool bigEndian) {
  std::uint64_t v = 0;
  for (int k = 0; k < p.countBytes; ++k) {
    const int byte = bigEndian ? k : p.countBytes - 1 - k;
    v = (v << 8) | static_cast<unsigned char>(bytes[byte]);
  }
  const std::uint64_t signBit = std::uint64_t(1) << (8 * p.countBytes - 1);
  if (p.countSigned && (v & signBit) != 0) return ~std::uint64_t(0);  // negative: refused
  return v;
}

// A binary body holds exactly the bytes the header declares: walks every list's count. Only the
// first `dataBytes` bytes of `data` count (not the newline loadMesh appends).
void checkPlyBinaryBody(const std::string& data, std::size_t dataBytes, const PlyHeader& header,
                        const std::string& path) {
  const bool bigEndian = header.encoding == PlyEncoding::kBinaryBigEndian;
  TriangleTally triangles(path, "PLY");
  // A file that ends with `end_header` has its line end only from loadMesh: no body bytes.
  std::size_t pos = std::min(header.bodyOffset, dataBytes);
  auto truncated = [&](const PlyElement& e, std::uint64_t i) {
    return InputError("PLY file " + path + " is truncated: " + std::to_string(dataBytes) +
                      " bytes end in " + declaredInstance(e, i));
  };
  for (const PlyElement& e : header.elements) {
    const bool hasList = std::any_of(e.properties.begin(), e.properties.end(),
                                     [](const PlyProperty& p) { return p.isList; });
    if (!hasList) {
      std::uint64_t recordBytes = 0;
      for (const PlyProperty& p : e.properties) recordBytes += std::uint64_t(p.valueBytes);
      const std::uint64_t left = dataBytes - pos;
      if (e.count > left / recordBytes)
        throw InputError("PLY file " + path + " declares " + std::to_string(e.count) + " " +
                         e.name + " records of " + std::to_string(recordBytes) +
                         " bytes but has only " + std::to_string(left) + " bytes left");
      pos += std::size_t(e.count * recordBytes);
      continue;
    }
    // Every instance takes at least one byte, so this bounds the walk by the file size.
    if (e.count > dataBytes - pos) throw truncated(e, 0);
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& p : e.properties) {
        if (!p.isList) {
          if (std::size_t(p.valueBytes) > dataBytes - pos) throw truncated(e, i);
          pos += std::size_t(p.valueBytes);
          continue;
        }
        if (std::size_t(p.countBytes) > dataBytes - pos) throw truncated(e, i);
        const std::uint64_t items = readPlyCount(data.data() + pos, p, bigEndian);
        pos += std::size_t(p.countBytes);
        if (items > (dataBytes - pos) / std::size_t(p.valueBytes)) throw truncated(e, i);
        if (isFaceElement(e)) triangles.addPolygon(items);
        pos += std::size_t(items) * std::size_t(p.valueBytes);
      }
    }
  }
}

// `data` ends in a newline, which loadMesh appended when the file's `dataBytes` did not.
void checkPlyData(const std::string& data, std::size_t dataBytes, const std::string& path) {
  const PlyHeader header = parsePlyHeader(data, path);
  checkPlyCounts(header, path);
  if (header.encoding == PlyEncoding::kAscii) {
    checkPlyAsciiBody(data, header, path);
  } else {
    checkPlyBinaryBody(data, dataBytes, header, path);
  }
}

// ---- OBJ sanity check -------------------------------------------------------------------------

// Counts `v` lines and the triangles of `f` lines against the caps; Assimp's OBJ reader checks
// the rest.
void checkObjData(const std::string& data, const std::string& path) {
  std::size_t vertices = 0;
  TriangleTally triangles(path, "OBJ");
  std::size_t pos = 0;
  while (pos < data.size()) {
    std::size_t end = data.find('\n', pos);
    if (end == std::string::npos) end = data.size();
    std::size_t i = pos;
    while (i < end && (data[i] == ' ' || data[i] == '\t')) ++i;
    if (i + 1 < end && (data[i + 1] == ' ' || data[i + 1] == '\t')) {
      if (data[i] == 'v') ++vertices;
      if (data[i] == 'f')
        triangles.addPolygon(countWords(std::string_view(data).substr(i + 1, end - i - 1)));
    }
    pos = end + 1;
  }
  if (vertices > kMaxMeshVertices)
    throw InputError("OBJ file " + path + " declares " + std::to_string(vertices) +
                     " vertices; at most " + std::to_string(kMaxMeshVertices));
}

// ---- Assimp -----------------------------------------------------------------------------------

// Refuses every file: an OBJ's `mtllib` must not make the importer open other files (only the
// geometry is used, and those files would escape the checks above).
class NoFilesIOSystem : public Assimp::IOSystem {
 public:
  bool Exists(const char*) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char*, const char*) override { return nullptr; }
  void Close(Assimp::IOStream* stream) override { delete stream; }
};

// The imported meshes before post-processing: every face's indices in range, counts under the
// caps, and primitive types that match the faces (Assimp's triangulation asserts on a mesh
// marked as holding polygons that has none, which a face with no index produces).
void checkImportedMeshes(const aiScene& scene, const std::string& path) {
  std::size_t vertices = 0, triangles = 0;
  for (unsigned mi = 0; mi < scene.mNumMeshes; ++mi) {
    const aiMesh& m = *scene.mMeshes[mi];
    vertices += m.mNumVertices;
    bool hasPolygon = false;
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices == 0 || face.mIndices == nullptr)
        throw InputError("mesh file " + path + " has a face with no vertices");
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= m.mNumVertices)
          throw InputError("mesh file " + path + " has an out-of-range vertex index");
      hasPolygon = hasPolygon || face.mNumIndices > 3;
      if (face.mNumIndices >= 3) triangles += face.mNumIndices - 2;
    }
    if ((m.mPrimitiveTypes & aiPrimitiveType_POLYGON) != 0 && !hasPolygon)
      throw InputError("malformed mesh file " + path + ": polygons declared but none found");
  }
  if (vertices > kMaxMeshVertices)
    throw InputError("mesh file " + path + " holds " + std::to_string(vertices) +
                     " vertices; at most " + std::to_string(kMaxMeshVertices));
  if (triangles > kMaxMeshTriangles)
    throw InputError("mesh file " + path + " holds " + std::to_string(triangles) +
                     " triangles; at most " + std::to_string(kMaxMeshTriangles));
}

bool withinCoordinateCap(const aiVector3D& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
         std::abs(p.x) <= kMaxMeshCoordinate && std::abs(p.y) <= kMaxMeshCoordinate &&
         std::abs(p.z) <= kMaxMeshCoordinate;
}

// Copies the triangles of every mesh into one Mesh, checking each position and index again.
Mesh collectTriangles(const aiScene& scene, const std::string& path) {
  Mesh mesh;
  for (unsigned mi = 0; mi < scene.mNumMeshes; ++mi) {
    const aiMesh* m = scene.mMeshes[mi];
    if ((m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
    const unsigned base = unsigned(mesh.positions.size());
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const aiVector3D& p = m->mVertices[v];
      if (!withinCoordinateCap(p))
        throw InputError("mesh file " + path +
                         " has a vertex coordinate that is not finite or exceeds " +
                         shortNumber(kMaxMeshCoordinate) + " in magnitude");
      mesh.positions.push_back({p.x, p.y, p.z});
      glm::vec3 n(0, 1, 0);
      if (m->mNormals != nullptr) {
        const aiVector3D& a = m->mNormals[v];
        const glm::vec3 candidate(a.x, a.y, a.z);
        const float length = glm::length(candidate);
        if (std::isfinite(length) && length > 0) n = candidate / length;
      }
      mesh.normals.push_back(n);
    }
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by the importer
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= m->mNumVertices)
          throw InputError("mesh file " + path + " has an out-of-range vertex index");
        mesh.indices.push_back(base + face.mIndices[k]);
      }
    }
  }
  return mesh;
}

}  // namespace

Mesh loadMesh(const std::string& path) {
  const MeshFileKind kind = classifyMeshFile(path);
  std::string data = readMeshFileBytes(path);
  if (kind.gzipped) data = gunzipMeshBytes(data, path);
  if (data.empty()) throw InputError("mesh file " + path + " is empty");
  // Assimp's line readers stop at a line end: give the last line one (std::string keeps a
  // NUL after it that Assimp is not told about).
  const std::size_t dataBytes = data.size();
  if (data.back() != '\n') data.push_back('\n');
  if (kind.format == MeshFormat::kPly) {
    checkPlyData(data, dataBytes, path);
  } else {
    checkObjData(data, path);
  }

  Assimp::Importer importer;
  importer.SetIOHandler(new NoFilesIOSystem);  // the importer owns and deletes it
  const char* hint = kind.format == MeshFormat::kPly ? "ply" : "obj";
  const aiScene* scene =
      importer.ReadFileFromMemory(data.data(), data.size(), aiProcess_ValidateDataStructure, hint);
  if (scene == nullptr || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0)
    throw InputError("malformed mesh file " + path + ": " + importer.GetErrorString());
  checkImportedMeshes(*scene, path);
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                       aiProcess_GenSmoothNormals | aiProcess_FindInvalidData);
  if (scene == nullptr)
    throw InputError("malformed mesh file " + path + ": " + importer.GetErrorString());

  Mesh mesh = collectTriangles(*scene, path);
  if (mesh.indices.empty()) throw InputError("mesh file " + path + " contains no triangles");
  mesh.closed = isClosedManifold(mesh);
  return mesh;
}

void normalizeMesh(Mesh& mesh, float size, const std::string& name) {
  if (!std::isfinite(size) || size <= 0)
    throw InputError(name + ": size " + shortNumber(size) + " must be positive and finite");
  Bounds b;
  for (const glm::vec3& p : mesh.positions) b.extend(p);
  const glm::vec3 extent = b.hi - b.lo;
  const float largest = std::max({extent.x, extent.y, extent.z});
  const float s = size / largest;
  if (b.empty() || !std::isfinite(largest) || largest <= 0 || !std::isfinite(s) || s <= 0)
    throw InputError(name + " has a zero or non-finite extent (" + shortNumber(largest) +
                     "); it cannot be scaled to size " + shortNumber(size));
  const glm::vec3 offset(b.center().x, b.lo.y, b.center().z);
  for (glm::vec3& p : mesh.positions) p = (p - offset) * s;
}

}  // namespace sl
